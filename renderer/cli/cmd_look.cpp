// `pelage look MESH`: from a mesh to a picture in one command. Grows a preset's pattern
// on the mesh, frames it (three-quarter view, ground, sun and sky), writes the scene
// file next to the output and renders it, so the user continues from that scene.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "renderer/animation/rig.h"
#include "renderer/camera/auto_frame.h"
#include "renderer/cli/common.h"
#include "renderer/cli/frame_list.h"
#include "renderer/cli/look_objects.h"
#include "renderer/cli/look_scene.h"
#include "renderer/cli/render_plan.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_objects.h"
#include "sim/mosaic/cell_types.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct LookOptions {
    std::string mesh, preset = "giraffe-reticulata", output, res = "960x540", up = "y",
                      view = "Filmic";
    uint64_t seed = 1;
    int spp = 64;
    bool fur = false, cryptomatte = false;
    std::string clip, frames;
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
    // --- Everything checked before anything is written ---
    // The animal's name: the object chosen in the file, else the file's name.
    const bool procedural = o.mesh.rfind("procedural:", 0) == 0;
    const sim::MeshSpec spec =
        procedural ? sim::MeshSpec{} : sim::parse_mesh_spec(o.mesh);
    const std::string animal = procedural ? "procedural"
                               : !spec.object.empty()
                                   ? spec.object
                                   : fs::path(spec.path).stem().string();
    fs::path output = o.output;
    if (output.empty()) output = animal + ".exr";
    if (output.extension() != ".exr")
        throw InputError("", 0, "-o",
                         "\"" + output.string() +
                             "\": the render is written as OpenEXR "
                             "(.exr)");
    const fs::path dir = fs::absolute(output).parent_path().lexically_normal();
    if (!fs::is_directory(dir))
        throw InputError(
            "", 0, "-o",
            "\"" + output.string() + "\": folder " + dir.string() + " does not exist");
    int width = 0, height = 0;
    parse_resolution(o.res, 65536, &width, &height);
    const Vec3f up = parse_up(o.up);
    // A bad preset fails here; one with an anisotropy field combs the fur along it.
    const bool preset_field =
        sim::load_preset(o.preset, data_path("scenes/presets"))
            .params.anisotropy_field.kind != sim::FieldSpec::Kind::none;
    // A file of several objects: the pattern goes on the animal, the rest as they come.
    LookObjects objects;
    if (!procedural && spec.object.empty()) {
        const double up_d[3] = {up.x, up.y, up.z};
        objects = choose_look_objects(spec.path, up_d);
    }
    const std::string grown_on =
        objects.animal.empty() ? o.mesh : spec.path + "#" + objects.animal;
    sim::MeshLoadReport report;
    sim::TriangleMesh mesh = sim::load_mesh(grown_on, &report);
    // The triangles' corners: an object's mesh may keep every vertex of its file.
    std::vector<Vec3f> points;
    auto add_corners = [&](const sim::TriangleMesh &m) {
        std::vector<char> used(m.positions.size(), 0);
        for (const auto &t : m.triangles)
            for (sim::VertId v : t) used[v] = 1;
        for (size_t v = 0; v < m.positions.size(); ++v)
            if (used[v])
                points.push_back({float(m.positions[v].x), float(m.positions[v].y),
                                  float(m.positions[v].z)});
    };
    // A clip: the frames asked for (by default the whole clip once), and the camera
    // framed on every pose of them.
    std::vector<int> frames;
    float rest_radius = 0;
    int last_frame = 0;
    Vec3f rest_long_axis{0, 0, 0};
    if (!o.clip.empty()) {
        const Rig rig = Rig::read(grown_on);
        const int clip = rig.clip(o.clip, "--clip");
        const double duration = rig.duration_seconds(clip);
        if (!o.frames.empty()) {
            const std::vector<FrameRange> ranges =
                parse_frame_ranges(o.frames, 1, "--frames");
            frames = expand_frames(ranges);
            // The scene's animation reaches every range's end ("0-100x24" ends at 100,
            // though its last frame is 96), so `render --frames` takes the same list.
            for (const FrameRange &r : ranges) last_frame = std::max(last_frame, r.last);
        }
        if (frames.empty())
            for (int f = 0; f < std::max(1, int(std::ceil(duration * o.fps - 1e-9))); ++f)
                frames.push_back(f);
        add_corners(mesh);
        FramingRequest rest_request;
        rest_request.up = up;
        const Framing rest_framing = frame_points(points, rest_request);
        rest_radius = rest_framing.radius;
        rest_long_axis = rest_framing.long_axis;
        points.clear();
        unweld(report, &mesh);
        for (int f : frames) {
            pose_mesh(rig, clip, clip_time(f / o.fps, duration, true), &mesh);
            add_corners(mesh);
        }
    } else {
        if (!o.frames.empty())
            throw InputError("", 0, "--frames", "needs --clip (the animation to play)");
        if (o.shutter > 0)
            throw InputError("", 0, "--shutter", "needs --clip (the animation to blur)");
        add_corners(mesh);
    }

    FramingRequest framing;
    framing.up = up;
    framing.aspect = float(width) / float(height);
    framing.long_axis = rest_long_axis;
    LookSetup setup;
    setup.framing = frame_points(points, framing);
    setup.up = up;
    const std::string stem = output.stem().string();
    setup.mesh = mesh_reference(grown_on, dir);
    if (!objects.animal.empty()) {
        setup.object_name = objects.animal;
        // The file's own floor, when one lies at the animal's feet, stands for the
        // ground (two coincident planes would flicker).
        const float radius = setup.framing.radius;
        for (const LookObject &p : objects.others) {
            // What the clip moves of the file's other objects (a rider, a harness,
            // eyes) plays it too.
            bool animated = false;
            if (!o.clip.empty()) {
                const Rig prop_rig = Rig::read(spec.path + "#" + p.name);
                animated = prop_rig.moves_mesh(prop_rig.clip(o.clip, "--clip"));
            }
            setup.props.push_back({p.name, mesh_reference(spec.path + "#" + p.name, dir),
                                   p.materials, p.missing_texture.empty(), animated});
            if (!p.missing_texture.empty())
                std::fprintf(
                    stderr, "pelage look: %s#%s: no image %s; its colours only\n",
                    spec.path.c_str(), p.name.c_str(), p.missing_texture.c_str());
            if (p.flat && p.flat_facing_up &&
                std::abs(p.flat_height - setup.framing.ground) <= 0.05 * radius)
                setup.ground = false;
        }
        std::string rest;
        for (const LookObject &p : objects.others)
            rest += (rest.empty() ? "\"" : ", \"") + p.name + "\"";
        std::fprintf(stderr,
                     "pelage look: %s holds %zu objects; growing the pattern on \"%s\" "
                     "(the largest that is not flat), the others (%s) in the file's "
                     "materials; select another with %s#NAME\n",
                     spec.path.c_str(), objects.others.size() + 1, objects.animal.c_str(),
                     rest.c_str(), spec.path.c_str());
        if (objects.left_out > 0)
            std::fprintf(stderr,
                         "pelage look: %s: %zu triangles belong to no object a name "
                         "selects on its own and are left out\n",
                         spec.path.c_str(), objects.left_out);
    }
    setup.cells = stem + ".cells";
    setup.output = output.filename().string();
    setup.preview = stem + "_preview.png";
    if (!o.clip.empty()) {
        // One image per frame: the frame number before the extension.
        setup.output = stem + ".####.exr";
        setup.preview = stem + "_preview.####.png";
        setup.clip = o.clip;
        setup.frames = std::max(frames.back(), last_frame) + 1;
        setup.fps = o.fps;
        setup.shutter = o.shutter;
        setup.body_radius = rest_radius;
    }
    if (!procedural && objects.animal.empty()) setup.object_name = animal;
    setup.preset = o.preset;
    setup.seed = o.seed;
    setup.width = width;
    setup.height = height;
    setup.spp = o.spp;
    setup.view = o.view;
    setup.fur = o.fur;
    setup.comb_field = preset_field;

    const fs::path scene_path = dir / (stem + ".json");
    const std::string scene_text = format_scene_json(look_scene(setup));
    write_file_atomically(scene_path.string(),
                          [&](std::ostream &out) { out << scene_text; });
    if (!o.quiet)
        fmt::print(
            "pelage look: wrote {} (radius {:.4g}, camera at {:.4g} radii); "
            "edit it and run `pelage render {}`\n",
            scene_path.string(), setup.framing.radius,
            length(setup.framing.camera.position - setup.framing.center) /
                setup.framing.radius,
            scene_path.string());

    RenderCliOptions ro;
    ro.scene = scene_path.string();
    ro.quiet = o.quiet;
    ro.cryptomatte = o.cryptomatte;
    ro.threads = o.threads;
    ro.stats_json = o.stats_json;
    if (!o.clip.empty())
        ro.frames = o.frames.empty() ? "0-" + std::to_string(frames.back()) : o.frames;
    return run_render(ro);
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
    o->stats_json.add_to(*sub, "the render's timing and ray counts");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
