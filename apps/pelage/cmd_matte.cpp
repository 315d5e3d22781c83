// `pelage matte IMAGE.exr --layer type --name F -o spots.png`: a Cryptomatte matte out
// of a rendered EXR, without a compositor (renderer/image/cryptomatte_read.h); `--list`
// prints the layers and the names their manifests hold. --stats-json keys: image, layer,
// names (those matched), width, height, coverage (the mean of the matte), pixels_covered
// (pixels with any coverage).
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/common/common.h"
#include "renderer/image/cryptomatte_read.h"
#include "renderer/image/image_output.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

struct MatteCliOptions {
    std::string image, layer = "object", output;
    std::vector<std::string> names;
    bool list = false;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

int run(const MatteCliOptions &o) {
    if (o.list) {
        for (const CryptomatteManifest &m : read_cryptomatte_manifests(o.image)) {
            std::printf("%s: %zu names\n", m.layer.c_str(), m.ids.size());
            for (const auto &[name, id] : m.ids) std::printf("  %s\n", name.c_str());
        }
        return 0;
    }
    if (o.names.empty())
        throw InputError("", 0, "--name", "give at least one name (or --list)");
    if (o.output.empty()) throw InputError("", 0, "-o", "give the matte's file");
    const std::filesystem::path dir =
        std::filesystem::absolute(std::filesystem::path(o.output)).parent_path();
    if (!std::filesystem::is_directory(dir))
        throw InputError(
            "", 0, "-o",
            "\"" + o.output + "\": folder " + dir.string() + " does not exist");
    const Matte m = read_cryptomatte_matte(o.image, o.layer, o.names);
    std::string ext = std::filesystem::path(o.output).extension().string();
    for (char &c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".exr") {
        ImageLayers l;
        l.width = m.width;
        l.height = m.height;
        l.names = {"A"};
        l.half = {0};
        l.pixels = m.alpha;
        ImageMetadata meta;
        meta.software = "pelage " PELAGE_VERSION;
        meta.scene = std::filesystem::absolute(o.image).string();
        write_exr(o.output, l, meta);
    } else if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
        // Coverage is a fraction, not a colour: stored as code values linearly.
        std::vector<unsigned char> rgb(size_t(m.width) * m.height * 3);
        for (size_t i = 0; i < m.alpha.size(); ++i)
            rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = static_cast<unsigned char>(
                std::lround(std::clamp(m.alpha[i], 0.0f, 1.0f) * 255));
        write_rgb8(o.output, m.width, m.height, rgb);
    } else {
        throw InputError("", 0, "-o",
                         "\"" + o.output + "\": write the matte as .exr, .png or .jpg");
    }
    if (!o.quiet)
        std::printf("%s: %zu name(s) of %s\n", o.output.c_str(), m.names.size(),
                    o.layer.c_str());
    if (o.stats_json.wanted()) {
        double sum = 0;
        size_t covered = 0;
        for (const float a : m.alpha) {
            sum += a;
            covered += a > 0;
        }
        o.stats_json.write({{"image", o.image},
                            {"layer", o.layer},
                            {"names", m.names},
                            {"width", m.width},
                            {"height", m.height},
                            {"coverage", m.alpha.empty() ? 0.0 : sum / m.alpha.size()},
                            {"pixels_covered", covered},
                            {"output", o.output}});
    }
    return 0;
}

}  // namespace

Runner add_matte_command(CLI::App &app) {
    auto o = std::make_shared<MatteCliOptions>();
    CLI::App *sub = app.add_subcommand(
        "matte", "Extract a Cryptomatte matte from a rendered EXR (or --list the names)");
    sub->add_option("image", o->image, "EXR rendered with film.cryptomatte")->required();
    sub->add_option("--layer", o->layer,
                    "Matte layer: object, type, cell, lineage (or CryptoObject, ...)")
        ->capture_default_str();
    sub->add_option("--name", o->names,
                    "Names to select ('*' matches any characters); repeatable");
    sub->add_option("-o,--output", o->output, "Matte file: .exr (float) or .png/.jpg");
    sub->add_flag("--list", o->list, "Print each layer's names and exit");
    o->stats_json.add_to(*sub, "the matte's names and coverage");
    o->quiet.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
