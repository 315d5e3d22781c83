// `pelage bench fur-colour`: does the fur keep the pattern's colours? Each preset is
// grown on the mesh and rendered by `pelage look` bare and with `--fur` (same camera,
// light and cells), both with Cryptomatte; for each cell type the mean linear colour over
// the pixels its type matte covers fully (apps/tools/matte_colour.h) is compared:
// luminance furry / bare, and the chromaticities R/G and B/G furry over bare. And the
// colour inversion against the forward model: a slab of fibres of each requested colour,
// as deep as asked, on a skin of that colour, in a white furnace, and the fraction of
// the light it reflects (the definition renderer/bsdf/hair_pigments.h inverts). Each
// render is a child `pelage` process, so the numbers are what a user gets.
#include <fmt/core.h>

#include <cmath>
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
    std::string mesh = "scenes/meshes/cow.off", res = "480x270", fur_keys = "{}",
                integrator_keys = "{}";
    std::vector<std::string> presets = {"giraffe-reticulata", "zebra", "teo-cheetah"};
    std::vector<std::string> slab_colours = {"0.9,0.7,0.5", "0.3,0.15,0.08",
                                             "0.04,0.02,0.01"};
    int spp = 64, slab_spp = 128;
    float beta_n = 0.3f;
    std::vector<float> slab_depths = {2, 26};
    std::vector<float> slab_comb = {20, 12};  // angle, jitter (degrees)
    uint64_t seed = 1;
    ThreadOption threads;
    BenchOutput out;
};

void run_or_throw(const std::string &command) {
    if (std::system((command + " >/dev/null").c_str()) != 0)
        throw std::runtime_error("bench fur-colour: `" + command + "` failed");
}

nlohmann::json rgb(Rgb c) { return {c.x, c.y, c.z}; }

// The views a slab's albedo is measured from: x = cos² of the angle from the normal and
// the weight of 3-point Gauss–Legendre in x on [0, 1], so the weighted mean of the
// furnace's radiance is the coat's bihemispherical albedo (fit_hair_coat.py).
struct SlabView {
    double x, weight;
};
const SlabView slab_views[] = {{0.5 - 0.5 * std::sqrt(0.6), 5.0 / 18},
                               {0.5, 8.0 / 18},
                               {0.5 + 0.5 * std::sqrt(0.6), 5.0 / 18}};

// A coat of fibres of `colour` `depth` fibre cross-sections deep (fur_depth in
// renderer/fur/strand_groom.h) on a skin of the same colour, lit by a white furnace,
// seen from `view`: what a hair colour means (sigma_a_from_coat_colour). The strands are
// `pelage look`'s coat (tapered 4:1, combed 20° with 12° of jitter, lengths ±30 %), on
// which the inversion's table was measured (renderer/bsdf/fit_hair_coat.py); other
// coats are the reach of `--slab-comb`: the same depth combed steeper reflects less. The
// slab is the unbiased coat the table measured: no path regularisation
// (integrator.fur_bounce_roughness), whose bias the furry renders show.
nlohmann::json slab_scene(const nlohmann::json &colour, float depth, float beta_n,
                          int spp, const std::string &output, SlabView view, float comb,
                          float jitter) {
    const double length = 0.25, root_radius = 0.002, tip_radius = 0.0005;
    const double density =
        depth / (length * (root_radius + tip_radius) * std::cos(comb * M_PI / 180));
    const double mu = std::sqrt(view.x), side = std::sqrt(1 - view.x) / std::sqrt(2.0);
    return {{"camera",
             {{"position", {3 * side, 3 * mu, 3 * side}},
              {"look_at", {0, 0, 0}},
              {"up", {0, 1, 0}},
              {"fov", 8}}},
            {"film", {{"width", 24}, {"height", 24}, {"spp", spp}, {"output", output}}},
            {"lights", {{{"type", "environment"}, {"colour", {1, 1, 1}}}}},
            {"integrator",
             {{"max_depth", 1024}, {"rr_depth", 1000}, {"fur_bounce_roughness", 0}}},
            {"objects",
             {{{"name", "slab"},
               {"mesh", "procedural:plane:1x1"},
               {"transform", {{"scale", 3}}},
               {"material", {{"shader", "diffuse"}, {"params", {{"albedo", colour}}}}},
               {"fur",
                {{"density", density},
                 {"length", length},
                 {"length_variation", 0.3},
                 {"root_radius", root_radius},
                 {"tip_radius", tip_radius},
                 {"segments", 6},
                 {"comb", {1, 0, 0}},
                 {"comb_angle", comb},
                 {"comb_jitter", jitter},
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
        for (const float depth : o.slab_depths) {
            Rgb m{0, 0, 0};
            for (const SlabView &view : slab_views) {
                std::ofstream(scene)
                    << slab_scene(colour, depth, o.beta_n, o.slab_spp, exr.string(), view,
                                  o.slab_comb[0], o.slab_comb[1]);
                run_or_throw(fmt::format("{} render {} --cryptomatte -q --threads {}",
                                         shell_quoted(self), shell_quoted(scene.string()),
                                         o.threads.threads));
                m = m + mean_rgb(exr.string()) * float(view.weight);
            }
            nlohmann::json error = nlohmann::json::array();
            for (int k = 0; k < 3; ++k)
                error.push_back(m[k] / colour[k].get<double>() - 1);
            runs.push_back({{"requested", colour},
                            {"depth", depth},
                            {"measured", rgb(m)},
                            {"relative_error", error}});
        }
    }
    return runs;
}

int run(const BenchFurColourOptions &o) {
    const nlohmann::json keys = nlohmann::json::parse(o.fur_keys, nullptr, false);
    if (!keys.is_object())
        throw InputError("", 0, "--fur-keys", "expected a JSON object of fur keys");
    const nlohmann::json integrator =
        nlohmann::json::parse(o.integrator_keys, nullptr, false);
    if (!integrator.is_object())
        throw InputError("", 0, "--integrator-keys",
                         "expected a JSON object of integrator keys");
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
            if (keys.empty() && integrator.empty()) {
                run_or_throw(look + size + " --fur -o " + shell_quoted(fur.string()));
            } else {
                // The scene `look --fur` writes, its fur and integrator blocks amended,
                // rendered again.
                run_or_throw(look + " --res 16x9 --spp 1 --fur -o " +
                             shell_quoted(fur.string()));
                const fs::path scene = fur.parent_path() / "animal.json";
                nlohmann::json j;
                std::ifstream(scene) >> j;
                for (const auto &[k, v] : keys.items()) j["objects"][0]["fur"][k] = v;
                for (const auto &[k, v] : integrator.items()) j["integrator"][k] = v;
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
                {"integrator_keys", integrator},
                {"presets", presets},
                {"slab_spp", o.slab_spp},
                {"slab_comb", o.slab_comb},
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
    cmd->add_option("--slab-depths", o->slab_depths,
                    "The slabs' depths: mean fibre cross-sections over a point of skin")
        ->delimiter(',')
        ->check(CLI::Range(0.1, 100.0))
        ->capture_default_str();
    cmd->add_option("--slab-comb", o->slab_comb,
                    "The slabs' comb angle and jitter in degrees (`look`'s: 20,12)")
        ->delimiter(',')
        ->expected(2)
        ->check(CLI::Range(0.0, 80.0))
        ->capture_default_str();
    cmd->add_option("--beta-n", o->beta_n, "The slabs' azimuthal roughness")
        ->check(CLI::Range(0.01, 1.0))
        ->capture_default_str();
    cmd->add_option(
           "--integrator-keys", o->integrator_keys,
           "A JSON object of integrator keys that amend the furry render's, e.g. "
           "'{\"max_depth\": 16}'")
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
