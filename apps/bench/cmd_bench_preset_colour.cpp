// `pelage bench preset-colour`: does the picture show a preset's colours? Each preset is
// grown on the mesh by `pelage look`, whose scene is rendered with Cryptomatte, then
// again with every cell type grey (albedo `--grey`, through clonal_mosaic's `types`:
// same cells, camera, light and samples). For each type, over the pixels its matte
// covers with their whole filter footprint (apps/tools/matte_colour.h), the colour the
// type shows under that light is
//     apparent = grey · mean(render) / mean(grey render)      (per channel, linear),
// the albedo a grey card of known reflectance calibrates: the light, its colour and the
// shading cancel, what the skin's BSDF adds or takes does not. Reported against the
// preset's colour as ΔE*ab (CIE 1976, apps/tools/colour_difference.h) and per-channel
// ratios. Under a Lambertian skin apparent equals the albedo up to inter-reflection
// and noise; a glossy coat's reflection of the sky lifts dark types and tints them blue.
// Each render is a child `pelage` process, so the numbers are what a user gets.
#include <fmt/core.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "apps/bench/bench.h"
#include "apps/tools/colour_difference.h"
#include "apps/tools/matte_colour.h"
#include "sim/core/input_error.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct BenchPresetColourOptions {
    std::string mesh = "scenes/meshes/cow.off", res = "640x360", bsdf = "look";
    std::vector<std::string> presets = {"leopard",
                                        "snow-leopard",
                                        "cheetah",
                                        "jaguar",
                                        "serval",
                                        "ocelot",
                                        "tiger",
                                        "puma",
                                        "lion",
                                        "zebra",
                                        "plains-zebra",
                                        "giraffe-reticulata",
                                        "holstein-cow",
                                        "giraffe-rothschildi",
                                        "giraffe-tippelskirchi"};
    int spp = 8, erode = 2;
    float grey = 0.5f, min_coverage = 0.99f;
    uint64_t seed = 1;
    ThreadOption threads;
    BenchOutput out;
};

void run_or_throw(const std::string &command) {
    if (std::system((command + " >/dev/null").c_str()) != 0)
        throw std::runtime_error("bench preset-colour: `" + command + "` failed");
}

nlohmann::json rgb(Rgb c) { return {c.x, c.y, c.z}; }

// The animal's material in `scene`: `bsdf` "look" keeps look's own, "lambert" and
// "coated" replace it (a coat keeps look's roughness and ior when it has them).
void set_bsdf(nlohmann::json *scene, const std::string &bsdf) {
    for (nlohmann::json &object : (*scene)["objects"]) {
        nlohmann::json &m = object["material"];
        if (m.value("shader", "") != "clonal_mosaic" || bsdf == "look") continue;
        m["bsdf"] = bsdf;
        if (bsdf == "lambert") {
            m.erase("roughness");
            m.erase("ior");
        }
    }
}

// Every cell type of the animal grey, through clonal_mosaic's `types`.
void set_grey(nlohmann::json *scene, const sim::Preset &preset, float grey) {
    nlohmann::json types = nlohmann::json::object();
    for (const sim::CellType &t : preset.types.types())
        types[t.name] = {{"colour", {grey, grey, grey}}};
    for (nlohmann::json &object : (*scene)["objects"])
        if (object["material"].value("shader", "") == "clonal_mosaic")
            object["material"]["params"]["types"] = types;
}

// One preset: its renders in `dir` and the measurement of each type.
nlohmann::json measure(const BenchPresetColourOptions &o, const std::string &self,
                       const std::string &name, const fs::path &dir) {
    const sim::Preset preset =
        sim::load_preset(name, data_path("scenes/presets"), "", "--presets");
    fs::create_directories(dir);
    // look grows the cells and writes its scene (with a 16x9 picture); both renders
    // are of that scene, by the same command, so they draw the same samples.
    run_or_throw(fmt::format(
        "{} look {} --preset {} --seed {} --threads {} --res 16x9 --spp 1 -q -o {}",
        shell_quoted(self), shell_quoted(o.mesh), shell_quoted(name), o.seed,
        o.threads.threads, shell_quoted((dir / "animal.exr").string())));
    nlohmann::json scene;
    std::ifstream(dir / "animal.json") >> scene;
    set_bsdf(&scene, o.bsdf);
    auto render = [&](const nlohmann::json &s, const std::string &stem) {
        const fs::path file = dir / (stem + ".json"), exr = dir / (stem + ".exr");
        std::ofstream(file) << s.dump(2);
        run_or_throw(
            fmt::format("{} render {} --cryptomatte -q --threads {} --res {} "
                        "--spp {} -o {}",
                        shell_quoted(self), shell_quoted(file.string()),
                        o.threads.threads, o.res, o.spp, shell_quoted(exr.string())));
        return exr.string();
    };
    const std::string colour_exr = render(scene, "colour");
    set_grey(&scene, preset, o.grey);
    const std::string grey_exr = render(scene, "grey");

    nlohmann::json types = nlohmann::json::array();
    double worst = 0;
    for (const MatteColourPair &m :
         mean_colours_by_matte(colour_exr, grey_exr, "type", o.min_coverage, o.erode)) {
        const int k = preset.types.find(m.name);
        if (k < 0) continue;  // a name the preset does not have (none from look)
        const std::array<float, 3> &c = preset.types[k].colour;
        const Rgb want{c[0], c[1], c[2]};
        nlohmann::json t = {{"type", m.name},
                            {"pixels", m.pixels},
                            {"preset_colour", rgb(want)},
                            {"rendered", rgb(m.mean)},
                            {"grey_rendered", rgb(m.other_mean)}};
        if (m.pixels > 0 && m.other_mean.x > 0 && m.other_mean.y > 0 &&
            m.other_mean.z > 0) {
            const Rgb apparent{o.grey * m.mean.x / m.other_mean.x,
                               o.grey * m.mean.y / m.other_mean.y,
                               o.grey * m.mean.z / m.other_mean.z};
            const double de = delta_e76(apparent, want);
            worst = std::max(worst, de);
            nlohmann::json ratio = nlohmann::json::array();
            for (int c = 0; c < 3; ++c)
                ratio.push_back(want[c] > 0 ? apparent[c] / want[c] : 0.0);
            t["apparent"] = rgb(apparent);
            t["ratio"] = ratio;
            t["delta_e76"] = de;
        }
        types.push_back(t);
    }
    return {{"preset", name},
            {"animal", preset.animal},
            {"types", types},
            {"max_delta_e76", worst}};
}

int run(const BenchPresetColourOptions &o) {
    if (o.bsdf != "look" && o.bsdf != "lambert" && o.bsdf != "coated")
        throw InputError("", 0, "--bsdf",
                         "\"" + o.bsdf + "\": expected look, lambert or coated");
    const std::string self = self_path();
    const fs::path dir = fs::temp_directory_path() /
                         fmt::format("pelage-bench-preset-colour-{}", ::getpid());
    nlohmann::json presets = nlohmann::json::array();
    try {
        for (const std::string &name : o.presets)
            presets.push_back(measure(o, self, name, dir / fs::path(name).stem()));
    } catch (...) {
        fs::remove_all(dir);
        throw;
    }
    fs::remove_all(dir);
    o.out.emit({{"mesh", o.mesh},
                {"res", o.res},
                {"spp", o.spp},
                {"seed", o.seed},
                {"bsdf", o.bsdf},
                {"grey", o.grey},
                {"erode", o.erode},
                {"min_coverage", o.min_coverage},
                {"definition",
                 "apparent = grey * mean(render) / mean(grey render) per linear channel "
                 "over the pixels whose (2 erode + 1)^2 neighbourhood the type's matte "
                 "covers at least min_coverage; delta_e76 = CIE 1976 Delta E*ab between "
                 "apparent and the preset's colour, both as linear sRGB (D65) "
                 "reflectances"},
                {"presets", presets}});
    return 0;
}

}  // namespace

Runner add_bench_preset_colour(CLI::App &bench) {
    auto o = std::make_shared<BenchPresetColourOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "preset-colour",
        "Each preset's colours as `look` shows them: per cell type, the colour under "
        "look's light (calibrated by a grey render) against the preset's, as CIE "
        "Delta E*ab (JSON)");
    cmd->add_option("--mesh", o->mesh, "The animal")->capture_default_str();
    cmd->add_option("--presets", o->presets, "Presets to render")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--res", o->res, "Resolution WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--spp", o->spp, "Samples per pixel")
        ->check(CLI::Range(1, 1 << 16))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the patterns")->capture_default_str();
    cmd->add_option("--bsdf", o->bsdf,
                    "The skin: look (what `pelage look` writes), lambert or coated")
        ->capture_default_str();
    cmd->add_option("--grey", o->grey, "The grey render's albedo")
        ->check(CLI::Range(0.05, 1.0))
        ->capture_default_str();
    cmd->add_option("--erode", o->erode,
                    "Pixels counted: those whose neighbours within this many pixels "
                    "the matte covers too (the film filter's reach)")
        ->check(CLI::Range(0, 8))
        ->capture_default_str();
    cmd->add_option("--min-coverage", o->min_coverage, "A pixel's least matte coverage")
        ->check(CLI::Range(0.5, 1.0))
        ->capture_default_str();
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
