// `pelage compare SCENE.json`: one render per shader on the scene's patterned objects,
// timings and a labelled contact sheet (apps/tools/compare.h). --stats-json keys are
// a contract: shaders {NAME: {seconds, ns_per_lookup}}, ratios, ratio_rounds,
// lookup_ratios.
#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "apps/common/common.h"
#include "apps/tools/compare.h"
#include "pattern/bake/bake.h"
#include "renderer/image/contact_sheet.h"
#include "renderer/image/image_output.h"
#include "renderer/job/scene_patterns.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_write_obj.h"

namespace pelage::renderer::cli {
namespace {

struct CompareCliOptions {
    std::string scene, shaders = "clonal_mosaic,worley,perlin,texture,diffuse", res,
                       sheet, view, atlas_res = "4096";
    int spp = 0;
    bool no_match = false;
    unsigned long long seed = 0;
    size_t lookups = 200000;
    int repeat = 1;
    bool deform = false;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

// A directory removed with everything in it when the comparison ends.
struct TempDir {
    std::filesystem::path path;
    ~TempDir() {
        std::error_code ec;
        if (!path.empty()) std::filesystem::remove_all(path, ec);
    }
};

// Whether the installed plugin `name` maps an image by UV (renderer::maps_image_by_uv).
bool maps_image(const renderer::PluginRegistry &plugins, const std::string &name) {
    const auto it = plugins.plugins().find(name);
    return it != plugins.plugins().end() && renderer::maps_image_by_uv(*it->second.desc);
}

// The texture baseline without a texture of its own: the mosaic baked into the CRPS atlas
// (`pelage bake`) with the mesh's atlas UVs, so a shader that maps an image by UV shows
// the same pattern as the mosaic. Bake time is not part of the texture render's time.
void bake_atlas_for_texture(const renderer::SceneDesc &desc, int res, TempDir &dir,
                            const renderer::PluginRegistry &plugins,
                            renderer::CompareOptions &co, bool quiet) {
    const renderer::ObjectDesc *subject = nullptr;
    for (const auto &obj : desc.objects)
        if (!obj.cells.empty()) {
            subject = &obj;
            break;
        }
    if (!subject || maps_image(plugins, subject->material.shader)) return;
    dir.path = std::filesystem::temp_directory_path() /
               fmt::format("pelage_compare_{}", getpid());
    std::filesystem::create_directories(dir.path);
    const Timer timer;
    const pattern::mosaic::MosaicPattern pattern(subject->cells, subject->mesh);
    const pattern::bake::BakedAtlas baked = pattern::bake::bake_atlas(pattern, res, res);
    co.texture_file = (dir.path / "atlas.exr").string();
    co.texture_mesh = (dir.path / "atlas.obj").string();
    co.texels_per_unit = float(baked.atlas.texels_per_unit);
    renderer::write_exr(co.texture_file, res, res, baked.image.tiles.at(0).pixels,
                        pattern::bake::BakeResult::channel_names(), false, {});
    std::vector<sim::Vec2d> uvs;
    for (sim::TriId t = 0; t < pattern.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) uvs.push_back(baked.atlas.uv(t, c));
    sim::write_obj(co.texture_mesh, pattern.surface().mesh, uvs,
                   "pelage compare: CRPS atlas UVs");
    if (!quiet)
        fmt::print(
            "texture: baked the mosaic into a {}x{} atlas ({:.1f} texels per unit) in "
            "{:.2f} s\n",
            res, res, baked.atlas.texels_per_unit, timer.seconds());
}

// The timings, each shader's, then the mosaic's ratio to each baseline.
void print_summary(const renderer::CompareResult &r, const nlohmann::json &report) {
    for (const auto &run : r.runs)
        fmt::print("{:<14} render {:8.3f} s ({:8.3f} s CPU)   shade {:8.1f} ns/lookup\n",
                   run.shader, run.seconds, run.cpu_seconds, run.ns_per_lookup);
    for (const auto &[k, v] : report["ratios"].items()) {
        fmt::print("  render {:<32} {:.3f}", k, v.get<double>());
        if (report["repeats"].get<size_t>() > 1 && report["ratio_rounds"].contains(k)) {
            const auto &rounds = report["ratio_rounds"][k];
            fmt::print("   (rounds {:.3f} … {:.3f}, median {:.3f})",
                       rounds["min"].get<double>(), rounds["max"].get<double>(),
                       rounds["median"].get<double>());
        }
        fmt::print("\n");
    }
    for (const auto &[k, v] : report["lookup_ratios"].items())
        fmt::print("  lookup {:<32} {:.3f}\n", k, v.get<double>());
}

int run(const CompareCliOptions &o) {
    const auto control = o.threads.apply();
    renderer::SceneDesc desc = renderer::load_scene_file(o.scene);
    grow_scene_patterns(desc, bool(o.quiet));
    if (o.spp > 0) desc.film.spp = o.spp;
    if (!o.res.empty())
        parse_resolution(o.res, 16384, &desc.film.width, &desc.film.height);
    const int atlas_res =
        parse_resolution(o.atlas_res, 16384, ResolutionForm::square, "--atlas-res", 16)
            .width;
    renderer::CompareOptions co;
    co.seed = o.seed;
    co.lookups = o.lookups;
    co.repeats = o.repeat;
    co.shaders.clear();
    std::stringstream ss(o.shaders);
    for (std::string s; std::getline(ss, s, ',');)
        if (!s.empty()) co.shaders.push_back(s);
    if (co.shaders.empty()) throw InputError("", 0, "--shaders", "no shader named");
    co.match_baselines = !o.no_match;
    if (o.deform) {
        // --- Pattern drift between the rest mesh and the deformed pose; no renders ---
        if (!o.sheet.empty())
            throw InputError("", 0, "--sheet",
                             "--deform measures drift; it draws no sheet");
        const renderer::DriftResult d = renderer::measure_pattern_drift(desc, co);
        if (!o.quiet) {
            fmt::print(
                "pattern drift, {} -> {} (mean |albedo change| at {} fixed surface "
                "points)\n",
                desc.objects[d.object].mesh, d.pose,
                d.runs.empty() ? 0 : d.runs[0].points);
            for (const auto &run : d.runs)
                fmt::print("{:<14} drift mean {:.6f}   max {:.6f}\n", run.shader,
                           run.mean, run.max);
        }
        o.stats_json.write(d.report());
        return 0;
    }
    // The display is checked before any rendering, so a bad view fails fast.
    std::optional<renderer::DisplayTransform> display;
    if (!o.sheet.empty()) display.emplace(o.view.empty() ? desc.film.view : o.view, "");

    TempDir atlas_dir;
    const renderer::PluginRegistry plugins;
    if (std::any_of(co.shaders.begin(), co.shaders.end(),
                    [&](const std::string &s) { return maps_image(plugins, s); }))
        bake_atlas_for_texture(desc, atlas_res, atlas_dir, plugins, co, bool(o.quiet));
    const renderer::CompareResult r = renderer::compare_shaders(desc, co);
    const nlohmann::json report = r.report();
    if (!o.quiet) print_summary(r, report);
    o.stats_json.write(report);
    if (display) {
        std::vector<renderer::SheetImage> images;
        for (const auto &run : r.runs) images.push_back({run.shader, &run.rgb});
        if (!renderer::write_contact_sheet(o.sheet, r.width, r.height, images, *display))
            std::fprintf(stderr,
                         "pelage compare: warning: no label font; %s is unlabelled\n",
                         o.sheet.c_str());
    }
    return 0;
}

}  // namespace

Runner add_compare_command(CLI::App &app) {
    auto o = std::make_shared<CompareCliOptions>();
    CLI::App *sub = app.add_subcommand(
        "compare",
        "Render a scene once per shader (CM vs Worley, Perlin, ...) and compare");
    sub->add_option("scene", o->scene, "Scene file (.json) with a patterned object")
        ->required();
    sub->add_option("--shaders", o->shaders, "Comma-separated shaders, in sheet order");
    sub->add_option("--res", o->res, "Resolution WIDTHxHEIGHT (overrides the scene)");
    sub->add_option("--spp", o->spp, "Samples per pixel (overrides the scene)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--sampler-seed", o->seed,
                    "Seed of the sampler, the same for every shader");
    refuse_pattern_seed(*sub, "--sampler-seed");
    sub->add_option("--lookups", o->lookups, "Surface points timed per shader")
        ->check(CLI::Range(size_t(1), size_t(100000000)));
    sub->add_option("--repeat", o->repeat,
                    "Render every shader N times, alternating, and report each one's "
                    "minimum time (for shared, noisy machines)")
        ->check(CLI::Range(1, 1000));
    o->stats_json.add_to(*sub, "the comparison");
    sub->add_option("--atlas-res", o->atlas_res,
                    "Side of the square atlas baked for the texture shader (N or NxN)")
        ->capture_default_str();
    sub->add_flag("--no-match", o->no_match,
                  "Baselines with their plugin defaults instead of the mosaic's colours "
                  "and spot density");
    sub->add_flag("--deform", o->deform,
                  "Pattern drift: albedo change at fixed surface points between the rest "
                  "mesh and the object's \"deform\" pose or its clip at eight times, per "
                  "shader (no renders)");
    sub->add_option("--sheet", o->sheet, "Write a labelled contact sheet (.png/.jpg)");
    sub->add_option("--view", o->view, "OCIO view for the sheet (default: the scene's)");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
