// `pelage look MESH`: from a mesh to a picture in one command. Grows a preset's pattern
// on the mesh, frames it (three-quarter view, ground, sun and sky), writes the scene
// file next to the output and renders it, so the user continues from that scene.
#include <fmt/core.h>

#include <cstdio>
#include <memory>
#include <string>

#include "apps/common/common.h"
#include "apps/pelage/export_report.h"
#include "apps/pelage/job_report.h"
#include "renderer/core/setup_phase.h"
#include "renderer/look/look.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

struct LookOptions {
    std::string mesh, preset = "giraffe-reticulata", output, res = "960x540", up = "y",
                      view = "Filmic";
    uint64_t seed = 1;
    int spp = 64;
    bool fur = false, cryptomatte = false, denoise = false;
    std::string clip, frames, export_path;
    int export_texture = 1024;
    double fps = 24;
    double shutter = 0;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

Vec3f parse_up(const std::string &text) {
    const std::pair<const char *, Vec3f> axes[] = {
        {"x", {1, 0, 0}},   {"y", {0, 1, 0}},   {"z", {0, 0, 1}},
        {"-x", {-1, 0, 0}}, {"-y", {0, -1, 0}}, {"-z", {0, 0, -1}}};
    for (const auto &[name, v] : axes)
        if (text == name) return v;
    throw InputError("", 0, "--up", "\"" + text + "\": expected x, y, z, -x, -y or -z");
}

int run(const LookOptions &o) {
    LookRequest request;
    request.mesh = o.mesh;
    request.preset = o.preset;
    request.presets_dir = data_path("scenes/presets");
    request.output = o.output;
    parse_resolution(o.res, 65536, &request.width, &request.height);
    request.spp = o.spp;
    request.up = parse_up(o.up);
    request.view = o.view;
    request.seed = o.seed;
    request.fur = o.fur;
    request.denoise = o.denoise;
    request.clip = o.clip;
    request.frames = o.frames;
    request.fps = o.fps;
    request.shutter = o.shutter;
    const LookPlan plan = plan_look(request, [](const std::string &w) {
        std::fprintf(stderr, "pelage look: %s\n", w.c_str());
    });

    // The scene is written beside the output for the user to continue from, and
    // rendered as written.
    const std::string scene_path = plan.scene_path.string();
    const std::string scene_text = format_scene_json(look_scene(plan.setup));
    write_file_atomically(scene_path, [&](std::ostream &out) { out << scene_text; });
    const Framing &framing = plan.setup.framing;
    if (!o.quiet)
        fmt::print(
            "pelage look: wrote {} (radius {:.4g}, camera at {:.4g} radii); "
            "edit it and run `pelage render {}`\n",
            scene_path, framing.radius,
            length(framing.camera.position - framing.center) / framing.radius,
            scene_path);

    RenderJob job = render_job_from_text(scene_text, scene_path);
    job.cryptomatte = o.cryptomatte;
    job.frames = plan.render_frames;
    JobReporting reporting;
    reporting.quiet = o.quiet;
    reporting.stats_json = o.stats_json;
    reporting.threads = o.threads.threads;
    const auto control = o.threads.apply();
    SetupPhase::show("render", o.quiet.progress());
    ExportJob exported;
    if (!o.export_path.empty()) {
        // Checked before the render, written after it: a bad path costs no render.
        exported.scene = job.scene;
        exported.output = o.export_path;
        exported.output_flag = "--export";
        exported.frames = plan.render_frames;
        exported.texture_size = o.export_texture;
        exported.command = "pelage look " + o.mesh;
        check_export_output(exported);
    }
    const int code = run_reported(std::move(job), reporting);
    if (code != 0 || o.export_path.empty()) return code;
    run_export_reported(exported, "pelage look", o.quiet);
    return 0;
}

}  // namespace

Runner add_look_command(CLI::App &app) {
    auto o = std::make_shared<LookOptions>();
    CLI::App *sub = app.add_subcommand(
        "look",
        "Grow a preset on a mesh, frame it and render it; writes the scene next to the "
        "output to continue from");
    sub->add_option("mesh", o->mesh,
                    "Mesh file (OFF, OBJ, PLY, glTF, FBX, ...; FILE#NAME for one object) "
                    "or procedural:...")
        ->required();
    sub->add_option(
           "--preset", o->preset,
           "Preset name (scenes/presets/NAME.json in pelage's data) or a preset file")
        ->capture_default_str();
    sub->add_option("--seed", o->seed, "Seed of the pattern")->capture_default_str();
    sub->add_option("-o,--output", o->output,
                    "Output EXR; the scene (.json), the cells (.cells) and the preview "
                    "(_preview.png) are written beside it (default: MESH_NAME.exr here)");
    sub->add_option("--res", o->res, "Resolution WIDTHxHEIGHT")->capture_default_str();
    sub->add_option("--spp", o->spp, "Samples per pixel")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    sub->add_option("--up", o->up, "The mesh's up axis: x, y, z, -x, -y or -z")
        ->capture_default_str();
    sub->add_option("--view", o->view, "OpenColorIO view of the preview")
        ->capture_default_str();
    sub->add_flag("--fur", o->fur, "Grow fur on the animal, scaled to its size");
    sub->add_option("--clip", o->clip,
                    "Play this animation clip of the mesh file (glTF, FBX, ...): one "
                    "image per frame, the camera framed on every pose");
    sub->add_option("--frames", o->frames,
                    "With --clip: the frames to render, e.g. 1-48 (default: the whole "
                    "clip once)");
    sub->add_option("--fps", o->fps, "With --clip: frames per second")
        ->capture_default_str()
        ->check(CLI::Range(0.001, 1000.0));
    sub->add_option("--shutter", o->shutter,
                    "With --clip: motion blur over this fraction of each frame, e.g. 0.5 "
                    "(animation.shutter [0, F])")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_flag("--cryptomatte", o->cryptomatte,
                  "Write every Cryptomatte layer the materials offer (the animal, its "
                  "cell types, cells and clones)");
    sub->add_flag("--denoise", o->denoise,
                  "Denoise the render (film.denoise): the preview shows the denoised "
                  "image, the EXR keeps the noisy one beside it");
    sub->add_option("--export", o->export_path,
                    "Also export the coat as OpenUSD (.usda; `pelage export`): the skin "
                    "with its pattern baked into a texture, the fur as coloured curves");
    sub->add_option("--export-texture", o->export_texture,
                    "With --export: the baked texture's side in texels")
        ->check(CLI::Range(16, 16384))
        ->capture_default_str();
    o->stats_json.add_to(*sub, "the render's timing and ray counts");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
