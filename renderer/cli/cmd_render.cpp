// `pelage render SCENE.json`: render a scene file to a multi-layer EXR (and optionally a
// display-referred PNG/JPEG preview through OpenColorIO).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "renderer/cli/common.h"
#include "renderer/core/progress.h"
#include "renderer/image/color_management.h"
#include "renderer/image/image_output.h"
#include "renderer/integrator/render.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"

namespace pelage::cli {
namespace {

namespace fs = std::filesystem;
using namespace pelage::renderer;

// Stopped by Ctrl-C: the shell convention 128 + SIGINT, so scripts can tell an
// interrupted render (whose EXR is whole but marked pelage:interrupted) from a failure.
constexpr int exit_interrupted = 128 + 2;

struct RenderCliOptions {
    std::string scene, output, preview, stats_json, res, view;
    int spp = 0;
    unsigned long long seed = 0;
    bool quiet = false, resume = false;
    std::string frames;
    int step = 1;
    ThreadOption threads;
};

std::string lower_extension(const std::string &path) {
    std::string e = fs::path(path).extension().string();
    for (char &c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// --frames A-B or A: the inclusive range, every `step`-th frame from A.
std::vector<int> parse_frames(const std::string &spec, int step,
                              const AnimationDesc &anim, const std::string &scene_path) {
    int a = 0, b = 0;
    char extra = 0;
    const int n = std::sscanf(spec.c_str(), "%d-%d%c", &a, &b, &extra);
    if (n == 1 && spec.find('-') == std::string::npos)
        b = a;
    else if (n != 2)
        throw InputError(
            "", 0, "--frames",
            "\"" + spec + "\": expected FIRST-LAST or one frame, e.g. 0-119");
    if (a < 0 || b < a)
        throw InputError("", 0, "--frames",
                         "\"" + spec + "\": frames are >= 0 and FIRST <= LAST");
    if (anim.present && b >= anim.frames)
        throw InputError(scene_path, 0, "animation.frames",
                         "--frames " + spec + " goes past the last frame (" +
                             std::to_string(anim.frames - 1) + ")");
    std::vector<int> frames;
    for (int f = a; f <= b; f += step) frames.push_back(f);
    return frames;
}

// out.####.exr → out.0007.exr: the last run of '#' becomes the zero-padded frame number.
std::string frame_path(const std::string &pattern, int frame) {
    const size_t last = pattern.find_last_of('#');
    if (last == std::string::npos) return pattern;
    size_t first = last;
    while (first > 0 && pattern[first - 1] == '#') --first;
    const std::string num = std::to_string(frame);
    const size_t width = last - first + 1;
    const std::string padded =
        num.size() >= width ? num : std::string(width - num.size(), '0') + num;
    return pattern.substr(0, first) + padded + pattern.substr(last + 1);
}

int run(const RenderCliOptions &o) {
    const auto control = o.threads.apply();
    SceneDesc desc = load_scene_file(o.scene);

    // --- Command-line overrides ---
    if (o.spp > 0) desc.film.spp = o.spp;
    if (!o.res.empty())
        parse_resolution(o.res, 65536, &desc.film.width, &desc.film.height);
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

    // --- Frames: --frames A-B [--step N], or the still (frame 0 of an animation) ---
    const bool animated = !o.frames.empty();
    const std::vector<int> frames =
        animated ? parse_frames(o.frames, o.step, desc.animation, o.scene)
                 : std::vector<int>{0};
    if (frames.size() > 1 && output.find('#') == std::string::npos)
        throw InputError("", 0, "-o",
                         "\"" + output +
                             "\": several frames need a #### in the file name "
                             "(replaced by the zero-padded frame number)");
    if (frames.size() > 1 && !preview.empty() && preview.find('#') == std::string::npos)
        throw InputError("", 0, "--preview",
                         "\"" + preview + "\": several frames need a #### in the name");
    if (o.resume && !animated)
        throw InputError("", 0, "--resume", "resumes a frame range: give --frames too");

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

    // --- Build the scene once when only the camera moves; per frame otherwise ---
    const PluginRegistry plugins;
    bool rigid = desc.animation.present;
    for (const auto &ob : desc.objects) rigid = rigid && ob.deform.empty();
    const auto &tt = desc.animation.turntable;
    if (tt && tt->target == TurntableDesc::Target::object) rigid = false;
    std::unique_ptr<Scene> shared_scene;
    if (rigid || !desc.animation.present)
        shared_scene = std::make_unique<Scene>(
            desc.animation.present ? scene_at_frame(desc, 0) : desc, plugins);

    InterruptGuard guard;
    nlohmann::json frame_stats = nlohmann::json::array();
    RenderStats total;
    double total_seconds = 0;
    int rendered = 0, skipped = 0, spp_done = desc.film.spp;
    bool interrupted = false;
    for (const int f : frames) {
        const std::string out_f = frame_path(output, f);
        const std::string preview_f = preview.empty() ? "" : frame_path(preview, f);
        if (o.resume) {
            std::string why;
            if (exr_is_complete(out_f, &why)) {
                ++skipped;
                if (!o.quiet) std::printf("%s: complete, skipped\n", out_f.c_str());
                continue;
            }
            if (!o.quiet && why != "no file")
                std::printf("%s: %s, rendering again\n", out_f.c_str(), why.c_str());
        }
        const SceneDesc fd = desc.animation.present ? scene_at_frame(desc, f) : desc;
        std::unique_ptr<Scene> own;
        if (!shared_scene) own = std::make_unique<Scene>(fd, plugins);
        const Scene &scene = shared_scene ? *shared_scene : *own;

        // --- Render; Ctrl-C stops at the next tile and keeps what is done ---
        RenderOptions ro;
        ro.seed = o.seed;
        ro.frame = uint32_t(f);
        ro.cancel = &InterruptGuard::flag();
        ro.progress = !o.quiet && Progress::stderr_is_tty();
        ro.camera = fd.camera;
        ro.instrument = !o.stats_json.empty();  // plugin_seconds
        if (tt && tt->motion_blur()) {
            const double open = f + double(tt->shutter_open),
                         span = double(tt->shutter_close - tt->shutter_open);
            ro.camera_motion = CameraMotion{&desc, open, span};
        }
        const RenderResult r = render(scene, ro);
        if (r.interrupted && animated) {
            // A partial frame never lands under its final name: --resume redoes it.
            std::fprintf(stderr,
                         "pelage render: interrupted during frame %d; %s not written\n",
                         f, out_f.c_str());
            return exit_interrupted;
        }

        // --- Write the outputs, atomically ---
        const std::vector<float> pixels = r.film->resolve();
        ImageMetadata meta;
        meta.scene = fs::absolute(o.scene).lexically_normal().string();
        meta.software = "pelage " PELAGE_VERSION;
        meta.spp = r.spp_done;
        meta.seed = o.seed;
        meta.render_seconds = r.seconds;
        meta.interrupted = r.interrupted;
        if (animated) {
            meta.frame = f;
            if (desc.animation.present) meta.fps = desc.animation.fps;
            meta.record_time = false;  // frames are byte-identical wherever rendered
        }
        write_exr(out_f, fd.film.width, fd.film.height, pixels,
                  Film::channel_names(scene.shader_aov_names()), fd.film.half, meta);
        if (display)
            write_preview(preview_f, fd.film.width, fd.film.height, pixels,
                          Film::num_channels, *display);
        ++rendered;
        total.add(r.stats);
        total_seconds += r.seconds;
        frame_stats.push_back({{"frame", f}, {"seconds", r.seconds}, {"output", out_f}});

        const double rays_per_second =
            r.seconds > 0 ? double(r.stats.rays()) / r.seconds : 0.0;
        if (!o.quiet)
            std::printf("%s: %dx%d, %d spp, %.2f s, %.2f Mrays/s%s\n", out_f.c_str(),
                        fd.film.width, fd.film.height, r.spp_done, r.seconds,
                        rays_per_second * 1e-6,
                        r.stats.nonfinite_samples
                            ? (", " + std::to_string(r.stats.nonfinite_samples) +
                               " non-finite samples dropped")
                                  .c_str()
                            : "");
        spp_done = std::min(spp_done, r.spp_done);
        if (r.interrupted) {
            std::fprintf(stderr,
                         "pelage render: interrupted; wrote %s with %d samples in every "
                         "pixel (more in some)\n",
                         out_f.c_str(), r.spp_done);
            interrupted = true;
            break;
        }
    }

    if (!o.stats_json.empty()) {
        const double rays_per_second =
            total_seconds > 0 ? double(total.rays()) / total_seconds : 0.0;
        nlohmann::json j = {{"seconds", total_seconds},
                            {"spp", spp_done},
                            {"width", desc.film.width},
                            {"height", desc.film.height},
                            {"rays", total.rays()},
                            {"rays_per_second", rays_per_second},
                            {"plugin_seconds", total.plugin_seconds()},
                            {"camera_rays", total.camera_rays},
                            {"secondary_rays", total.secondary_rays},
                            {"shadow_rays", total.shadow_rays},
                            {"samples", total.samples},
                            {"nonfinite_samples", total.nonfinite_samples},
                            {"plugin_calls", total.plugin_calls},
                            {"seed", o.seed},
                            {"threads", o.threads.threads},
                            {"interrupted", interrupted},
                            {"output", frame_path(output, frames.front())}};
        if (shared_scene) j["triangles"] = shared_scene->geometry().num_triangles();
        if (shared_scene && shared_scene->fur()) {  // fur (docs/guide/fur.md)
            j["fur_strands"] = shared_scene->fur()->num_strands();
            j["fur_grow_seconds"] = shared_scene->fur()->grow_seconds();
            j["fur_embree_seconds"] = shared_scene->fur()->embree_seconds();
        }
        if (animated) {
            j["frames"] = frame_stats;
            j["frames_rendered"] = rendered;
            j["frames_skipped"] = skipped;
        }
        write_json_file(o.stats_json, j);
    }
    if (animated && !o.quiet)
        std::printf("%d frame(s) rendered, %d skipped (complete), %.2f s\n", rendered,
                    skipped, total_seconds);
    return interrupted ? exit_interrupted : 0;
}

}  // namespace

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
    sub->add_option("--frames", o->frames,
                    "Frame range FIRST-LAST (or one frame); -o then names a sequence, "
                    "out.####.exr");
    sub->add_option("--step", o->step, "Every N-th frame of --frames")
        ->check(CLI::Range(1, 1000000));
    sub->add_flag("--resume", o->resume,
                  "Skip frames whose EXR is complete (header and pixel checksum)");
    sub->add_flag("-q,--quiet", o->quiet, "No progress bar, no summary line");
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::cli
