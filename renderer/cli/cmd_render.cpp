// `pelage render SCENE.json`: render a scene file to a multi-layer EXR (and optionally a
// display-referred PNG/JPEG preview through OpenColorIO).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "renderer/cli/common.h"
#include "renderer/color_management.h"
#include "renderer/image_output.h"
#include "renderer/progress.h"
#include "renderer/render.h"
#include "renderer/scene_file.h"
#include "sim/input_error.h"

namespace pelage::cli {
namespace {

namespace fs = std::filesystem;
using namespace pelage::renderer;

struct RenderCliOptions {
    std::string scene, output, preview, stats_json, res, view;
    int spp = 0;
    unsigned long long seed = 0;
    bool quiet = false;
    ThreadOption threads;
};

std::string lower_extension(const std::string &path) {
    std::string e = fs::path(path).extension().string();
    for (char &c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

int run(const RenderCliOptions &o) {
    const auto control = o.threads.apply();
    SceneDesc desc = load_scene_file(o.scene);

    // --- Command-line overrides ---
    if (o.spp > 0) desc.film.spp = o.spp;
    if (!o.res.empty()) parse_resolution(o.res, 65536, &desc.film.width, &desc.film.height);
    if (!o.view.empty()) desc.film.view = o.view;
    const std::string output = !o.output.empty() ? o.output : desc.film.output;
    if (output.empty())
        throw InputError(o.scene, 0, "film.output",
                         "no output file: give -o OUT.exr or set film.output");
    if (lower_extension(output) != ".exr")
        throw InputError("", 0, "-o",
                         "\"" + output + "\": the render is written as OpenEXR (.exr)");
    const std::string preview = !o.preview.empty() ? o.preview : desc.film.preview;
    std::optional<DisplayTransform> display;
    if (!preview.empty()) {
        const std::string e = lower_extension(preview);
        if (e != ".png" && e != ".jpg" && e != ".jpeg")
            throw InputError("", 0, "--preview",
                             "\"" + preview + "\": expected a .png or .jpg file");
        display.emplace(desc.film.view, "");  // checks the view before any work is done
    }

    // --- Fail before rendering, not after, when an output folder is missing ---
    for (const auto &[flag, file] : {std::pair<std::string, std::string>{"-o", output},
                                     {"--preview", preview},
                                     {"--stats-json", o.stats_json}}) {
        if (file.empty()) continue;
        const fs::path dir = fs::absolute(fs::path(file)).parent_path();
        if (!fs::is_directory(dir))
            throw InputError(
                "", 0, flag,
                "\"" + file + "\": folder " + dir.string() + " does not exist");
    }

    // --- Build the scene: plugins, meshes, Embree, lights ---
    const PluginRegistry plugins;
    const Scene scene(desc, plugins);

    // --- Render; Ctrl-C stops at the next tile and keeps what is done ---
    InterruptGuard guard;
    RenderOptions ro;
    ro.seed = o.seed;
    ro.cancel = &InterruptGuard::flag();
    ro.progress = !o.quiet && Progress::stderr_is_tty();
    const RenderResult r = render(scene, ro);

    // --- Write the outputs, atomically ---
    const std::vector<float> pixels = r.film->resolve();
    ImageMetadata meta;
    meta.scene = fs::absolute(o.scene).lexically_normal().string();
    meta.software = "pelage " PELAGE_VERSION;
    meta.spp = r.spp_done;
    meta.seed = o.seed;
    meta.render_seconds = r.seconds;
    meta.interrupted = r.interrupted;
    write_exr(output, desc.film.width, desc.film.height, pixels,
              Film::channel_names(scene.shader_aov_names()), desc.film.half, meta);
    if (display)
        write_preview(preview, desc.film.width, desc.film.height, pixels,
                      Film::num_channels, *display);

    const double rays_per_second =
        r.seconds > 0 ? double(r.stats.rays()) / r.seconds : 0.0;
    if (!o.stats_json.empty()) {
        write_json_file(o.stats_json, {{"seconds", r.seconds},
                                       {"spp", r.spp_done},
                                       {"width", desc.film.width},
                                       {"height", desc.film.height},
                                       {"rays", r.stats.rays()},
                                       {"rays_per_second", rays_per_second},
                                       {"plugin_seconds", r.stats.plugin_seconds()},
                                       {"camera_rays", r.stats.camera_rays},
                                       {"secondary_rays", r.stats.secondary_rays},
                                       {"shadow_rays", r.stats.shadow_rays},
                                       {"samples", r.stats.samples},
                                       {"nonfinite_samples", r.stats.nonfinite_samples},
                                       {"plugin_calls", r.stats.plugin_calls},
                                       {"triangles", scene.geometry().num_triangles()},
                                       {"seed", o.seed},
                                       {"threads", o.threads.threads},
                                       {"interrupted", r.interrupted},
                                       {"output", output}});
    }
    if (!o.quiet)
        std::printf("%s: %dx%d, %d spp, %.2f s, %.2f Mrays/s%s\n", output.c_str(),
                    desc.film.width, desc.film.height, r.spp_done, r.seconds,
                    rays_per_second * 1e-6,
                    r.stats.nonfinite_samples
                        ? (", " + std::to_string(r.stats.nonfinite_samples) +
                           " non-finite samples dropped")
                              .c_str()
                        : "");
    if (r.interrupted) {
        std::fprintf(stderr,
                     "pelage render: interrupted; wrote %s with %d samples in every "
                     "pixel (more in some)\n",
                     output.c_str(), r.spp_done);
        return 1;
    }
    return 0;
}

}  // namespace

Runner add_render_command(CLI::App &app) {
    auto o = std::make_shared<RenderCliOptions>();
    CLI::App *sub =
        app.add_subcommand("render", "Render a scene file to a multi-layer EXR");
    sub->add_option("scene", o->scene, "Scene file (JSON; see README, \"Scene files\")")
        ->required();
    sub->add_option("-o,--output", o->output,
                    "Output EXR (default: the scene's film.output)");
    sub->add_option("--spp", o->spp, "Samples per pixel (overrides film.spp)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--res", o->res,
                    "Resolution WIDTHxHEIGHT (overrides film.width/height)");
    sub->add_option(
        "--seed", o->seed,
        "Random seed; the same seed gives the same image at any thread count");
    sub->add_option("--preview", o->preview,
                    "Also write a PNG/JPEG preview through OpenColorIO");
    sub->add_option("--view", o->view,
                    "OpenColorIO view of the preview (default: film.view, \"Standard\")");
    sub->add_option("--stats-json", o->stats_json, "Write timing and ray counts as JSON");
    sub->add_flag("-q,--quiet", o->quiet, "No progress bar, no summary line");
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::cli
