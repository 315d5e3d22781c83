// `pelage render SCENE.json`: render a scene file to a multi-layer EXR (and optionally a
// display-referred PNG/JPEG preview through OpenColorIO).
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "renderer/camera/camera.h"
#include "renderer/cli/common.h"
#include "renderer/cli/grow_shown.h"
#include "renderer/cli/input_hash.h"
#include "renderer/cli/render_plan.h"
#include "renderer/cli/render_tiles.h"
#include "renderer/core/progress.h"
#include "renderer/image/color_management.h"
#include "renderer/image/frame_pattern.h"
#include "renderer/image/image_layers.h"
#include "renderer/image/image_output.h"
#include "renderer/integrator/render.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;
using namespace pelage::renderer;

// Stopped by Ctrl-C: the shell convention 128 + SIGINT, so scripts can tell an
// interrupted render (whose EXR is whole but marked pelage:interrupted) from a failure.
constexpr int exit_interrupted = 128 + 2;

// One scene for every frame when only the camera moves (and for a still); null when an
// object turns, deforms or grows, and each frame builds its own.
std::unique_ptr<Scene> shared_scene_for(const SceneDesc &desc,
                                        const PluginRegistry &plugins) {
    bool rigid = desc.animation.present;
    for (const auto &ob : desc.objects)
        rigid = rigid && ob.deform.empty() && !ob.grow && !ob.clip;
    const auto &tt = desc.animation.turntable;
    if (tt && tt->target == TurntableDesc::Target::object) rigid = false;
    if (!rigid && desc.animation.present) return nullptr;
    return std::make_unique<Scene>(
        desc.animation.present ? scene_at_frame(desc, 0) : desc, plugins);
}

// The totals over the frames of one run, for --stats-json and the summary line.
struct RunTotals {
    nlohmann::json frame_stats = nlohmann::json::array();
    RenderStats stats;
    double seconds = 0;  // rendering
    // Loading the scene and building meshes, fur and the BVH; writing the EXRs and
    // previews. With `seconds` they are most of the wall time.
    double setup_seconds = 0, write_seconds = 0;
    int rendered = 0, skipped = 0, spp_done = 0;
    bool interrupted = false;
};

enum class FrameOutcome {
    written,  // rendered (whole, or a still stopped by Ctrl-C) and written
    skipped,  // --resume found it complete
    aborted,  // a range interrupted mid-frame: nothing written, --resume redoes it
};

// The scene's Cryptomatte layers, named through the scene.
std::vector<CryptomatteSource> matte_sources(const Scene &scene) {
    std::vector<CryptomatteSource> sources;
    for (size_t l = 0; l < scene.matte_layers().size(); ++l)
        sources.push_back({scene.matte_layers()[l], [&scene, l](uint64_t key) {
                               return scene.matte_name(int(l), key);
                           }});
    return sources;
}

// What a compositor or a farm reads from the header besides the pixels: the camera,
// the compression, and the settings that made the image.
void describe_render(const SceneDesc &fd, ImageMetadata &meta) {
    const Camera camera(fd.camera, fd.film.width, fd.film.height);
    meta.world_to_camera = camera.world_to_camera();
    meta.world_to_ndc = camera.world_to_ndc();
    meta.compression = fd.film.compression;
    if (fd.animation.present && meta.fps <= 0) meta.fps = fd.animation.fps;
    const char *filters[] = {"box", "gaussian", "blackman_harris"};
    meta.strings.emplace_back(
        "pelage:filter",
        fmt::format("{} {:g}", filters[int(fd.film.filter)], fd.film.filter_radius));
    meta.strings.emplace_back("pelage:sampler",
                              fd.integrator.sampler == IntegratorDesc::SamplerKind::sobol
                                  ? "sobol"
                                  : "independent");
    const char *selection[] = {"auto", "all", "power", "uniform"};
    meta.strings.emplace_back("pelage:light_selection",
                              selection[int(fd.integrator.light_selection)]);
    meta.ints.emplace_back("pelage:max_depth", fd.integrator.max_depth);
    meta.ints.emplace_back("pelage:rr_depth", fd.integrator.rr_depth);
}

// Frame f: rendered (Ctrl-C stops at the next tile and keeps what is done), then its
// EXR and preview written atomically.
FrameOutcome render_frame(const RenderCliOptions &o, const SceneDesc &desc,
                          const RenderPlan &plan, const PluginRegistry &plugins,
                          const Scene *shared_scene, int f, RunTotals *totals) {
    const std::string out_f = substitute_frame(plan.output, f);
    const std::string preview_f =
        plan.preview.empty() ? "" : substitute_frame(plan.preview, f);
    const std::string settings = frame_settings_hash(plan.settings, f);
    if (o.resume) {
        std::string why;
        if (exr_is_complete(out_f, &why)) {
            // Complete is not enough: a frame of another resolution, spp or scene would
            // make a mixed sequence.
            const std::string recorded = recorded_settings_hash(out_f);
            const bool same_tile =
                !plan.tile ||
                exr_string_attribute(out_f, tile_attribute) == plan.tile->label();
            if (recorded == settings && same_tile) {
                ++totals->skipped;
                if (!o.quiet) std::printf("%s: complete, skipped\n", out_f.c_str());
                return FrameOutcome::skipped;
            }
            why = recorded.empty()       ? "complete but without pelage:settings_xxh3"
                  : recorded != settings ? "rendered with other settings"
                                         : "another tile";
        }
        if (!o.quiet && why != "no file")
            std::printf("%s: %s, rendering again\n", out_f.c_str(), why.c_str());
    }
    // Motion, poses and random numbers follow the frame's place in the animation, so
    // animation.first_frame renumbers the frames without changing them.
    const int local = f - desc.animation.first_frame;
    const SceneDesc fd = desc.animation.present ? scene_at_frame(desc, local) : desc;
    std::unique_ptr<Scene> own;
    double frame_setup_seconds = 0;
    if (!shared_scene) {
        const Timer setup;
        own = std::make_unique<Scene>(fd, plugins);
        frame_setup_seconds = setup.seconds();
        totals->setup_seconds += frame_setup_seconds;
    }
    const Scene &scene = shared_scene ? *shared_scene : *own;

    RenderOptions ro;
    ro.seed = o.seed;
    ro.frame = uint32_t(local);
    ro.cancel = &InterruptGuard::flag();
    ro.progress = o.quiet.progress();
    ro.camera = fd.camera;
    ro.instrument = o.stats_json.wanted();  // plugin_seconds
    const auto &tt = desc.animation.turntable;
    if (tt && tt->target == TurntableDesc::Target::camera &&
        desc.animation.motion_blur()) {
        const double open = local + double(desc.animation.shutter_open),
                     span = double(desc.animation.shutter_close) -
                            double(desc.animation.shutter_open);
        ro.camera_motion = CameraMotion{&desc, open, span};
    }
    if (plan.tile)
        ro.region = RenderOptions::Region{0, plan.tile_y0, fd.film.width, plan.tile_y1};
    const RenderResult r = render(scene, ro);
    if (r.interrupted && plan.animated) {
        std::fprintf(stderr,
                     "pelage render: interrupted during frame %d; %s not written\n", f,
                     out_f.c_str());
        return FrameOutcome::aborted;
    }

    const Timer writing;  // output: the layers resolved (Cryptomatte names), then written
    ImageLayers layers =
        image_layers(*r.film, fd.film, scene.shader_aov_names(), matte_sources(scene),
                     [](const std::string &w) {
                         std::fprintf(stderr, "pelage render: %s\n", w.c_str());
                     });
    ImageMetadata meta;
    meta.scene = fs::absolute(o.scene).lexically_normal().string();
    meta.software = "pelage " PELAGE_VERSION;
    meta.spp = r.spp_done;
    meta.seed = o.seed;
    meta.render_seconds = r.seconds;
    meta.interrupted = r.interrupted;
    meta.view = fd.film.view;  // `pelage movie` displays the frames through it
    meta.settings_xxh3 = settings;
    const double mean_spp =
        double(r.stats.samples) / (double(fd.film.width) * fd.film.height);
    meta.clamp_indirect = fd.integrator.clamp_indirect;
    if (fd.film.noise_threshold > 0) {
        meta.noise_threshold = fd.film.noise_threshold;
        meta.min_spp = fd.film.min_spp;
        meta.mean_spp = mean_spp;
    }
    if (plan.animated) {
        meta.frame = f;
        if (desc.animation.present) meta.fps = desc.animation.fps;
    }
    describe_render(fd, meta);
    // No render time in the file: a frame or still rendered again, on another machine
    // or as merged tiles, is the same file byte for byte (the time is in --stats-json).
    meta.record_time = false;
    if (plan.tile) {
        layers.pixels =
            tile_pixels(layers.pixels, fd.film.height, plan.tile_y0, plan.tile_y1);
        layers.height = plan.tile_y1 - plan.tile_y0;
        describe_tile(*plan.tile, fd.film.width, fd.film.height, plan.tile_y0,
                      plan.tile_y1, r.region_samples, r.region_spp_done, &meta);
    }
    write_exr(out_f, layers, meta);
    if (plan.display)
        write_preview(preview_f, fd.film.width, fd.film.height, layers.pixels,
                      layers.channels(), *plan.display);
    totals->write_seconds += writing.seconds();
    ++totals->rendered;
    totals->stats.add(r.stats);
    totals->seconds += r.seconds;
    nlohmann::json frame_stat = {{"frame", f}, {"seconds", r.seconds}, {"output", out_f}};
    if (own) {
        // A frame that builds its own scene (a clip, a deformation, growth): what the
        // pose and its fur cost, frame by frame.
        frame_stat["setup_seconds"] = frame_setup_seconds;
        frame_stat["pose_seconds"] = own->geometry().pose_seconds();
        if (own->fur()) {
            frame_stat["fur_strands"] = own->fur()->num_strands();
            frame_stat["fur_grow_seconds"] = own->fur()->grow_seconds();
            frame_stat["fur_embree_seconds"] = own->fur()->embree_seconds();
        }
        frame_stat["peak_rss_mb"] = peak_rss_mb();  // of the process so far
    }
    totals->frame_stats.push_back(frame_stat);

    const double rays_per_second =
        r.seconds > 0 ? double(r.stats.rays()) / r.seconds : 0.0;
    if (!o.quiet)
        std::printf("%s: %dx%d%s, %d spp%s, %.2f s, %.2f Mrays/s%s\n", out_f.c_str(),
                    fd.film.width, fd.film.height,
                    plan.tile ? (" tile " + plan.tile->label()).c_str() : "", meta.spp,
                    fd.film.noise_threshold > 0
                        ? fmt::format(" (adaptive, mean {:.1f})", meta.mean_spp).c_str()
                        : "",
                    r.seconds, rays_per_second * 1e-6,
                    r.stats.nonfinite_samples
                        ? (", " + std::to_string(r.stats.nonfinite_samples) +
                           " non-finite samples dropped")
                              .c_str()
                        : "");
    totals->spp_done = std::min(totals->spp_done, r.spp_done);
    if (r.interrupted) {
        std::fprintf(stderr,
                     "pelage render: interrupted; wrote %s with %d samples in every "
                     "pixel (more in some)\n",
                     out_f.c_str(), r.spp_done);
        totals->interrupted = true;
    }
    return FrameOutcome::written;
}

// The run's summary for --stats-json: the keys are a contract with scripts.
void write_stats_json(const RenderCliOptions &o, const SceneDesc &desc,
                      const RenderPlan &plan, const Scene *shared_scene,
                      const RunTotals &totals, double wall_seconds) {
    const double rays_per_second =
        totals.seconds > 0 ? double(totals.stats.rays()) / totals.seconds : 0.0;
    nlohmann::json j = {{"seconds", totals.seconds},
                        {"wall_seconds", wall_seconds},
                        {"setup_seconds", totals.setup_seconds},
                        {"write_seconds", totals.write_seconds},
                        {"spp", totals.spp_done},
                        {"width", desc.film.width},
                        {"height", desc.film.height},
                        {"rays", totals.stats.rays()},
                        {"rays_per_second", rays_per_second},
                        {"plugin_seconds", totals.stats.plugin_seconds()},
                        {"camera_rays", totals.stats.camera_rays},
                        {"secondary_rays", totals.stats.secondary_rays},
                        {"shadow_rays", totals.stats.shadow_rays},
                        {"samples", totals.stats.samples},
                        {"nonfinite_samples", totals.stats.nonfinite_samples},
                        {"plugin_calls", totals.stats.plugin_calls},
                        {"seed", o.seed},
                        {"threads", o.threads.threads},
                        {"interrupted", totals.interrupted},
                        {"output", substitute_frame(plan.output, plan.frames.front())}};
    if (shared_scene) j["triangles"] = shared_scene->geometry().num_triangles();
    if (shared_scene && shared_scene->fur()) {  // fur (docs/guide/fur.md)
        j["fur_strands"] = shared_scene->fur()->num_strands();
        j["fur_grow_seconds"] = shared_scene->fur()->grow_seconds();
        j["fur_embree_seconds"] = shared_scene->fur()->embree_seconds();
    }
    if (plan.tile) j["tile"] = plan.tile->label();
    if (plan.animated) {
        j["frames"] = totals.frame_stats;
        j["frames_rendered"] = totals.rendered;
        j["frames_skipped"] = totals.skipped;
    }
    o.stats_json.write(j);
}

}  // namespace

int run_render(const RenderCliOptions &o) {
    const Timer wall;
    const auto control = o.threads.apply();
    SetupPhase::show("render", o.quiet.progress());
    SceneDesc desc = load_scene_file(o.scene);
    RenderPlan plan = plan_render(o, desc);
    grow_scene_patterns(desc, bool(o.quiet));  // after the outputs are checked
    const PluginRegistry plugins;
    plan.settings = settings_hash(desc, plugins, o.seed, PELAGE_VERSION);
    const std::unique_ptr<Scene> shared_scene = shared_scene_for(desc, plugins);

    InterruptGuard guard;
    RunTotals totals;
    totals.setup_seconds = wall.seconds();
    totals.spp_done = desc.film.spp;
    for (const int f : plan.frames) {
        const FrameOutcome done =
            render_frame(o, desc, plan, plugins, shared_scene.get(), f, &totals);
        if (done == FrameOutcome::aborted) return exit_interrupted;
        if (totals.interrupted) break;
    }
    if (o.stats_json.wanted())
        write_stats_json(o, desc, plan, shared_scene.get(), totals, wall.seconds());
    if (plan.animated && !o.quiet)
        std::printf("%d frame(s) rendered, %d skipped (complete), %.2f s\n",
                    totals.rendered, totals.skipped, totals.seconds);
    if (!o.quiet)
        std::printf("wall %.2f s: set-up %.2f s, render %.2f s, writing %.2f s\n",
                    wall.seconds(), totals.setup_seconds, totals.seconds,
                    totals.write_seconds);
    return totals.interrupted ? exit_interrupted : 0;
}

Runner add_render_command(CLI::App &app) {
    auto o = std::make_shared<RenderCliOptions>();
    CLI::App *sub =
        app.add_subcommand("render", "Render a scene file to a multi-layer EXR");
    sub->add_option("scene", o->scene, "Scene file (JSON; docs/guide/scene-format.md)")
        ->required();
    sub->add_option("-o,--output", o->output,
                    "Output EXR (default: the scene's film.output)");
    sub->add_option("--spp", o->spp, "Samples per pixel (overrides film.spp)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--noise-threshold", o->noise_threshold,
                    "Adaptive sampling: a pixel stops once its noise is below this "
                    "(0.01 clean, 0.1 preview; 0 = off; overrides "
                    "film.noise_threshold); --spp is then the most a pixel takes")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--res", o->res,
                    "Resolution WIDTHxHEIGHT (overrides film.width/height)");
    sub->add_option(
        "--seed", o->seed,
        "Random seed; the same seed gives the same image at any thread count");
    sub->add_option("--preview", o->preview,
                    "Also write a PNG/JPEG preview through OpenColorIO");
    sub->add_option("--view", o->view,
                    "OpenColorIO view of the preview (default: film.view, \"Standard\")");
    o->stats_json.add_to(*sub, "timing and ray counts");
    sub->add_flag("--cryptomatte", o->cryptomatte,
                  "Write every Cryptomatte layer the materials offer (film.cryptomatte)");
    sub->add_option("--frames", o->frames,
                    "Frames: 1001-1120, 1,5,9, 1-100x5 (every 5th), 0-20x5,33; -o then "
                    "names a sequence, out.####.exr, out.%04d.exr or out.$F4.exr");
    sub->add_option("--step", o->step,
                    "Every N-th frame of each --frames range without its own xSTEP")
        ->check(CLI::Range(1, 1000000));
    sub->add_option("--tile", o->tile,
                    "Render tile I of N (1-based) of a still, rows (I-1)*H/N to I*H/N-1, "
                    "into -o; `pelage merge` joins the tiles");
    sub->add_flag("--resume", o->resume,
                  "Skip frames whose EXR is complete (header and pixel checksum) and "
                  "was rendered with the same settings (pelage:settings_xxh3)");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run_render(*o); };
}

}  // namespace pelage::renderer::cli
