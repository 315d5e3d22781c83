// `pelage merge TILES... -o OUT.exr`: joins the tiles `pelage render --tile I/N` wrote
// (renderer/job/render_tiles.h) into the whole still: the same file, byte for byte, as
// a whole render of it. The tiles must belong together: one pelage:settings_xxh3, one
// display window, one tile count, every tile present once and complete, each covering
// exactly its rows. Anything else is exit 2 naming the file, and nothing is written.
// --stats-json keys: output, width, height, tiles, spp, mean_spp, seconds.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/common/common.h"
#include "renderer/image/image_output.h"
#include "renderer/job/render_tiles.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct MergeOptions {
    std::vector<std::string> tiles;
    std::string output;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

struct TileFile {
    std::string path;
    OIIO::ImageSpec spec;
    TileSpec tile;
};

TileFile open_tile(const std::string &path) {
    std::string why;
    if (!exr_is_complete(path, &why))
        throw InputError(path, 0, "", "not a complete tile (" + why + ")");
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path, 0, "", "unreadable: " + OIIO::geterror());
    TileFile t{path, in->spec(), {}};
    const std::string label = t.spec.get_string_attribute(tile_attribute);
    if (label.empty())
        throw InputError(path, 0, tile_attribute,
                         "not a tile: pelage render --tile I/N writes tiles");
    t.tile = parse_tile(label, path + ": " + tile_attribute);
    return t;
}

// The tile's rows and columns must be exactly those of its index.
void check_window(const TileFile &t) {
    const OIIO::ImageSpec &s = t.spec;
    int y0 = 0, y1 = 0;
    tile_rows(t.tile, s.full_height, &y0, &y1, t.path);
    if (s.x != 0 || s.width != s.full_width || s.y != y0 || s.y + s.height != y1 ||
        s.full_x != 0 || s.full_y != 0)
        throw InputError(t.path, 0, "data window",
                         "rows " + std::to_string(s.y) + "-" +
                             std::to_string(s.y + s.height - 1) + " are not tile " +
                             t.tile.label() + "'s rows " + std::to_string(y0) + "-" +
                             std::to_string(y1 - 1));
}

// Every tile like the first: same settings, display window, tile count, channels.
void check_together(const TileFile &first, const TileFile &t) {
    auto refuse = [&](const std::string &field, const std::string &why) {
        throw InputError(t.path, 0, field, why + " (" + first.path + ")");
    };
    const std::string settings = first.spec.get_string_attribute("pelage:settings_xxh3");
    if (settings.empty())
        throw InputError(first.path, 0, "pelage:settings_xxh3", "missing");
    if (t.spec.get_string_attribute("pelage:settings_xxh3") != settings)
        refuse("pelage:settings_xxh3",
               "rendered with other settings than the first tile");
    if (t.tile.count != first.tile.count)
        refuse(tile_attribute, "one of " + std::to_string(t.tile.count) +
                                   " tiles, the first tile one of " +
                                   std::to_string(first.tile.count));
    if (t.spec.full_width != first.spec.full_width ||
        t.spec.full_height != first.spec.full_height)
        refuse("display window", "another image size than the first tile");
    if (t.spec.channelnames != first.spec.channelnames ||
        t.spec.channelformats != first.spec.channelformats)
        refuse("channels", "other channels than the first tile");
}

// The whole render's metadata, from its tiles': the same as the tile's but the whole
// image's spp (the most any tile took), mean spp (all the tiles' samples) and
// Cryptomatte manifests (every name some tile shows: a whole render lists the names its
// pixels show, in name order).
ImageMetadata whole_metadata(const std::vector<TileFile> &tiles) {
    const OIIO::ImageSpec &s = tiles.front().spec;
    ImageMetadata meta;
    meta.view = s.get_string_attribute("pelage:view");
    meta.compression = s.get_string_attribute("compression", "zip");
    std::array<float, 16> m;
    if (s.getattribute("worldtocamera", OIIO::TypeMatrix, m.data()))
        meta.world_to_camera = m;
    if (s.getattribute("worldtoNDC", OIIO::TypeMatrix, m.data())) meta.world_to_ndc = m;
    for (const char *k : {"pelage:filter", "pelage:sampler", "pelage:light_selection"})
        if (const std::string v = s.get_string_attribute(k); !v.empty())
            meta.strings.emplace_back(k, v);
    for (const char *k : {"pelage:max_depth", "pelage:rr_depth"})
        if (s.find_attribute(k)) meta.ints.emplace_back(k, s.get_int_attribute(k));
    for (const auto &a : s.extra_attribs) {
        const std::string n = a.name().string();
        if (n.rfind("cryptomatte/", 0) != 0) continue;
        if (n.size() < 9 || n.compare(n.size() - 9, 9, "/manifest") != 0) {
            meta.strings.emplace_back(n, a.get_string());
            continue;
        }
        nlohmann::json all = nlohmann::json::object();
        for (const TileFile &t : tiles) {
            const auto j =
                nlohmann::json::parse(t.spec.get_string_attribute(n), nullptr, false);
            if (!j.is_object())
                throw InputError(t.path, 0, n, "is not a Cryptomatte manifest");
            all.update(j);
        }
        meta.strings.emplace_back(n, all.dump());
    }
    meta.scene = s.get_string_attribute("pelage:scene");
    meta.software = s.get_string_attribute("Software");
    meta.seed = std::stoull(s.get_string_attribute("pelage:seed", "0"));
    meta.settings_xxh3 = s.get_string_attribute("pelage:settings_xxh3");
    meta.clamp_indirect = s.get_float_attribute("pelage:clamp_indirect", 0);
    meta.fur_bounce_roughness = s.get_float_attribute("pelage:fur_bounce_roughness", 0);
    meta.noise_threshold = s.get_float_attribute("pelage:noise_threshold", 0);
    meta.min_spp = s.get_int_attribute("pelage:min_spp", 0);
    meta.frame = s.get_int_attribute("pelage:frame", -1);
    meta.fps = s.get_float_attribute("pelage:fps", 0);
    meta.record_time = false;
    uint64_t samples = 0;
    for (const TileFile &t : tiles) {
        meta.spp = std::max(meta.spp, t.spec.get_int_attribute("pelage:spp", 0));
        samples += std::stoull(t.spec.get_string_attribute(tile_samples_attribute, "0"));
    }
    meta.mean_spp = double(samples) / (double(s.full_width) * s.full_height);
    return meta;
}

int run(const MergeOptions &o) {
    const Timer timer;
    if (fs::path(o.output).extension() != ".exr")
        throw InputError("", 0, "-o", "\"" + o.output + "\": expected a .exr file");
    const fs::path dir = fs::absolute(fs::path(o.output)).parent_path();
    if (!fs::is_directory(dir))
        throw InputError(
            "", 0, "-o",
            "\"" + o.output + "\": folder " + dir.string() + " does not exist");
    std::vector<TileFile> tiles;
    std::map<int, std::string> seen;  // tile index -> file
    for (const std::string &path : o.tiles) {
        TileFile t = open_tile(path);
        if (!tiles.empty()) check_together(tiles.front(), t);
        check_window(t);
        const auto [it, fresh] = seen.emplace(t.tile.index, path);
        if (!fresh)
            throw InputError(
                path, 0, tile_attribute,
                "tile " + t.tile.label() + " again (also " + it->second + ")");
        tiles.push_back(std::move(t));
    }
    const int count = tiles.front().tile.count;
    std::string missing;
    for (int i = 1; i <= count; ++i)
        if (!seen.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
        throw InputError(
            "", 0, "TILES",
            "tile(s) " + missing + " of " + std::to_string(count) + " missing");

    const OIIO::ImageSpec &s = tiles.front().spec;
    const int W = s.full_width, H = s.full_height, nc = s.nchannels;
    ImageLayers whole;
    whole.width = W;
    whole.height = H;
    whole.names = s.channelnames;
    for (int c = 0; c < nc; ++c)
        whole.half.push_back(s.channelformat(c) == OIIO::TypeDesc::HALF);
    std::vector<float> &pixels = whole.pixels;
    pixels.resize(size_t(W) * H * nc);
    for (const TileFile &t : tiles) {
        auto in = OIIO::ImageInput::open(t.path);
        if (!in || !in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT,
                                   &pixels[size_t(t.spec.y) * W * nc]))
            throw std::runtime_error(t.path + ": cannot read pixels: " +
                                     (in ? in->geterror() : OIIO::geterror()));
    }
    const ImageMetadata meta = whole_metadata(tiles);
    write_exr(o.output, whole, meta);
    if (!o.quiet) std::printf("%s: %dx%d from %d tiles\n", o.output.c_str(), W, H, count);
    o.stats_json.write({{"output", o.output},
                        {"width", W},
                        {"height", H},
                        {"tiles", count},
                        {"spp", meta.spp},
                        {"mean_spp", meta.mean_spp},
                        {"seconds", timer.seconds()}});
    return 0;
}

}  // namespace

Runner add_merge_command(CLI::App &app) {
    auto o = std::make_shared<MergeOptions>();
    CLI::App *sub = app.add_subcommand(
        "merge", "Join the tiles of `pelage render --tile I/N` into the whole EXR");
    sub->add_option("tiles", o->tiles, "Tile EXRs, all N of them, in any order")
        ->required();
    sub->add_option("-o,--output", o->output, "The whole EXR")->required();
    o->stats_json.add_to(*sub, "the merged image's size, tiles and samples");
    o->quiet.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
