// `pelage bench fur-colour`: does the fur keep the pattern's colours? Each preset is
// grown on the mesh and rendered by `pelage look` bare and with `--fur` (same camera,
// light and cells), both with Cryptomatte; for each cell type the mean linear colour over
// the pixels its type matte covers fully (apps/tools/matte_colour.h) is compared:
// luminance furry / bare, and the chromaticities R/G and B/G furry over bare. And the
// colour inversion against the forward model: a thick slab of fibres of each requested
// colour in a white furnace (the definition renderer/bsdf/fit_hair_colour.py measures
// its table with) and the albedo it shows. Each render is a child `pelage` process, so
// the numbers are what a user gets.
#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "apps/bench/bench.h"
#include "apps/tools/matte_colour.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct BenchFurColourOptions {
    std::string mesh = "scenes/meshes/cow.off", res = "480x270", fur_keys = "{}";
    std::vector<std::string> presets = {"giraffe-reticulata", "zebra", "teo-cheetah"};
    std::vector<std::string> slab_colours = {"0.9,0.7,0.5", "0.3,0.15,0.08",
                                             "0.04,0.02,0.01"};
    int spp = 64, slab_spp = 128;
    float beta_n = 0.3f;
    uint64_t seed = 1;
    ThreadOption threads;
    BenchOutput out;
};

void run_or_throw(const std::string &command) {
    if (std::system((command + " >/dev/null").c_str()) != 0)
        throw std::runtime_error("bench fur-colour: `" + command + "` failed");
}

nlohmann::json rgb(Rgb c) { return {c.x, c.y, c.z}; }

// A thick slab of fibres of `colour` on a black skin, lit by a white furnace, seen
// straight down: about 30 fibre cross-sections over every point of the skin.
nlohmann::json slab_scene(const nlohmann::json &colour, float beta_n, int spp,
                          const std::string &output) {
    return {{"camera",
             {{"position", {0, 3, 0.001}},
              {"look_at", {0, 0, 0}},
              {"up", {0, 0, -1}},
              {"fov", 8}}},
            {"film", {{"width", 24}, {"height", 24}, {"spp", spp}, {"output", output}}},
            {"lights", {{{"type", "environment"}, {"colour", {1, 1, 1}}}}},
            {"integrator", {{"max_depth", 1024}, {"rr_depth", 1000}}},
            {"objects",
             {{{"name", "slab"},
               {"mesh", "procedural:plane:1x1"},
               {"transform", {{"scale", 3}}},
               {"material", {{"shader", "diffuse"}, {"params", {{"albedo", 0}}}}},
               {"fur",
                {{"density", 30000},
                 {"length", 0.25},
                 {"root_radius", 0.002},
                 {"tip_radius", 0.002},
                 {"segments", 4},
                 {"comb_angle", 30},
                 {"comb_jitter", 30},
                 {"colour", colour},
                 {"melanin_jitter", 0},
                 {"beta_n", beta_n},
                 {"max_strands", 50000000}}}}}}};
}

// The image's mean RGB.
Rgb mean_rgb(const std::string &exr) {
    const std::vector<MatteColour> all = mean_colour_by_matte(exr, "CryptoObject", 0);
    if (all.empty()) throw std::runtime_error("bench fur-colour: no slab in " + exr);
    return all[0].mean;
}

nlohmann::json slab_runs(const BenchFurColourOptions &o, const std::string &self,
                         const fs::path &dir) {
    nlohmann::json runs = nlohmann::json::array();
    for (const std::string &text : o.slab_colours) {
        nlohmann::json colour = nlohmann::json::array();
        for (size_t at = 0; at <= text.size();) {
            const size_t comma = std::min(text.find(',', at), text.size());
            const std::string number = text.substr(at, comma - at);
            char *end = nullptr;
            const double c = std::strtod(number.c_str(), &end);
            if (number.empty() || *end != 0 || !(c > 0 && c <= 1))
                throw InputError("", 0, "--slab-colours",
                                 "\"" + text + "\": expected r,g,b, each in (0, 1]");
            colour.push_back(c);
            at = comma + 1;
        }
        if (colour.size() != 3)
            throw InputError("", 0, "--slab-colours", "\"" + text + "\": expected r,g,b");
        fs::create_directories(dir / "slab");
        const fs::path scene = dir / "slab" / "slab.json",
                       exr = dir / "slab" / "slab.exr";
        std::ofstream(scene) << slab_scene(colour, o.beta_n, o.slab_spp, exr.string());
        run_or_throw(fmt::format("{} render {} --cryptomatte -q --threads {}",
                                 shell_quoted(self), shell_quoted(scene.string()),
                                 o.threads.threads));
        const Rgb m = mean_rgb(exr.string());
        nlohmann::json error = nlohmann::json::array();
        for (int k = 0; k < 3; ++k) error.push_back(m[k] / colour[k].get<double>() - 1);
        runs.push_back(
            {{"requested", colour}, {"measured", rgb(m)}, {"relative_error", error}});
    }
    return runs;
}

int run(const BenchFurColourOptions &o) {
    const nlohmann::json keys = nlohmann::json::parse(o.fur_keys, nullptr, false);
    if (!keys.is_object())
        throw InputError("", 0, "--fur-keys", "expected a JSON object of fur keys");
    const std::string self = self_path();
    const fs::path dir =
        fs::temp_directory_path() / fmt::format("pelage-bench-fur-colour-{}", ::getpid());
    nlohmann::json presets = nlohmann::json::array(), slab = nlohmann::json::array();
    try {
        if (o.slab_spp > 0) slab = slab_runs(o, self, dir);
        for (const std::string &preset : o.presets) {
            if (preset.empty()) continue;  // --presets "": the slabs only
            const std::string stem = fs::path(preset).stem().string();
            const fs::path bare = dir / stem / "bare" / "animal.exr",
                           fur = dir / stem / "fur" / "animal.exr";
            fs::create_directories(bare.parent_path());
            fs::create_directories(fur.parent_path());
            const std::string look = fmt::format(
                "{} look {} --preset {} --seed {} --threads {} --cryptomatte -q",
                shell_quoted(self), shell_quoted(o.mesh), shell_quoted(preset), o.seed,
                o.threads.threads);
            const std::string size = fmt::format(" --res {} --spp {}", o.res, o.spp);
            run_or_throw(look + size + " -o " + shell_quoted(bare.string()));
            if (keys.empty()) {
                run_or_throw(look + size + " --fur -o " + shell_quoted(fur.string()));
            } else {
                // The scene `look --fur` writes, its fur block amended, rendered again.
                run_or_throw(look + " --res 16x9 --spp 1 --fur -o " +
                             shell_quoted(fur.string()));
                const fs::path scene = fur.parent_path() / "animal.json";
                nlohmann::json j;
                std::ifstream(scene) >> j;
                for (const auto &[k, v] : keys.items()) j["objects"][0]["fur"][k] = v;
                std::ofstream(scene) << j.dump(2);
                run_or_throw(fmt::format("{} render {} --cryptomatte -q --threads {}",
                                         shell_quoted(self), shell_quoted(scene.string()),
                                         o.threads.threads) +
                             size);
            }
            const auto b = mean_colour_by_matte(bare.string(), "type");
            const auto f = mean_colour_by_matte(fur.string(), "type");
            nlohmann::json types = nlohmann::json::array();
            for (const MatteColour &bc : b)
                for (const MatteColour &fc : f) {
                    if (fc.name != bc.name || bc.pixels == 0 || fc.pixels == 0) continue;
                    const Rgb x = bc.mean, y = fc.mean;
                    types.push_back(nlohmann::json{
                        {"type", bc.name},
                        {"bare", rgb(x)},
                        {"fur", rgb(y)},
                        {"bare_pixels", bc.pixels},
                        {"fur_pixels", fc.pixels},
                        {"luminance_ratio", luminance(y) / std::max(luminance(x), 1e-9f)},
                        {"rg_ratio", (y.x / std::max(y.y, 1e-9f)) /
                                         std::max(x.x / std::max(x.y, 1e-9f), 1e-9f)},
                        {"bg_ratio", (y.z / std::max(y.y, 1e-9f)) /
                                         std::max(x.z / std::max(x.y, 1e-9f), 1e-9f)}});
                }
            presets.push_back({{"preset", stem}, {"types", types}});
        }
    } catch (...) {
        fs::remove_all(dir);
        throw;
    }
    fs::remove_all(dir);
    o.out.emit({{"mesh", o.mesh},
                {"res", o.res},
                {"spp", o.spp},
                {"seed", o.seed},
                {"fur_keys", keys},
                {"presets", presets},
                {"slab_spp", o.slab_spp},
                {"beta_n", o.beta_n},
                {"slab", slab}});
    return 0;
}

}  // namespace

Runner add_bench_fur_colour(CLI::App &bench) {
    auto o = std::make_shared<BenchFurColourOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "fur-colour",
        "Fur against the bare skin: each cell type's mean colour in both renders (JSON)");
    cmd->add_option("--mesh", o->mesh, "The animal")->capture_default_str();
    cmd->add_option("--presets", o->presets, "Presets, each rendered bare and furry")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--res", o->res, "Resolution WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--spp", o->spp, "Samples per pixel")
        ->check(CLI::Range(1, 1 << 16))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the patterns")->capture_default_str();
    cmd->add_option("--slab-colours", o->slab_colours,
                    "Colours r,g,b of the white-furnace slabs")
        ->capture_default_str();
    cmd->add_option("--slab-spp", o->slab_spp, "Samples per pixel of each slab (0: none)")
        ->check(CLI::Range(0, 1 << 16))
        ->capture_default_str();
    cmd->add_option("--beta-n", o->beta_n, "The slabs' azimuthal roughness")
        ->check(CLI::Range(0.01, 1.0))
        ->capture_default_str();
    cmd->add_option("--fur-keys", o->fur_keys,
                    "A JSON object of fur keys that amend `look --fur`'s fur block, e.g. "
                    "'{\"colour\": \"skin_melanin\", \"melanin_scale\": 2.5}'")
        ->capture_default_str();
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
