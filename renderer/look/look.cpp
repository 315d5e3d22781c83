#include "renderer/look/look.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "renderer/animation/rig.h"
#include "renderer/camera/body_facing.h"
#include "renderer/image/frame_pattern.h"
#include "renderer/job/frame_list.h"
#include "renderer/look/look_objects.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_objects.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer {

namespace {

namespace fs = std::filesystem;

// The points the camera frames: the triangles' corners (an object's mesh may keep every
// vertex of its file).
void add_corners(const sim::TriangleMesh &m, std::vector<Vec3f> *points) {
    std::vector<char> used(m.positions.size(), 0);
    for (const auto &t : m.triangles)
        for (sim::VertId v : t) used[v] = 1;
    for (size_t v = 0; v < m.positions.size(); ++v)
        if (used[v])
            points->push_back({float(m.positions[v].x), float(m.positions[v].y),
                               float(m.positions[v].z)});
}

// The mesh as a still shows it: a skinned file in its default pose (renderer/animation/
// rig.h pose_default), anything else as loaded.
sim::TriangleMesh still_mesh(const Rig *rig, const sim::MeshLoadReport &report,
                             sim::TriangleMesh mesh) {
    if (report.read.skinned_pieces > 0 && rig) pose_default(*rig, report, &mesh);
    return mesh;
}

// Which way the animal faces (body_facing.h), from the mesh a still shows: for a clip
// too, so every frame is seen from the side the still is, turned to the head.
BodyFacing mesh_facing(const sim::TriangleMesh &m, const std::string &path, Vec3f up) {
    std::vector<Vec3f> positions;
    positions.reserve(m.positions.size());
    for (const sim::Vec3d &p : m.positions)
        positions.push_back({float(p.x), float(p.y), float(p.z)});
    std::vector<std::array<uint32_t, 3>> triangles;
    triangles.reserve(m.triangles.size());
    for (const auto &t : m.triangles)
        triangles.push_back({uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2])});
    return body_facing(positions, triangles, up, format_front(path));
}

// A clip's frames and poses: the frames asked for (by default the whole clip once), the
// rest pose's size, and every pose's corners for the camera.
struct ClipPoses {
    std::vector<int> frames;
    int last_frame = 0;  // the last frame any range reaches
    float rest_radius = 0;
};

ClipPoses pose_clip(const LookRequest &o, const std::string &grown_on,
                    const sim::MeshLoadReport &report, sim::TriangleMesh mesh,
                    std::vector<Vec3f> *points) {
    ClipPoses c;
    const Rig rig = Rig::read(grown_on);
    const int clip = rig.clip(o.clip, "--clip");
    const double duration = rig.duration_seconds(clip);
    if (!o.frames.empty()) {
        const std::vector<FrameRange> ranges =
            parse_frame_ranges(o.frames, 1, "--frames");
        c.frames = expand_frames(ranges);
        // The scene's animation reaches every range's end ("0-100x24" ends at 100,
        // though its last frame is 96), so `render --frames` takes the same list.
        for (const FrameRange &r : ranges) c.last_frame = std::max(c.last_frame, r.last);
    }
    if (c.frames.empty())
        for (int f = 0; f < std::max(1, int(std::ceil(duration * o.fps - 1e-9))); ++f)
            c.frames.push_back(f);
    add_corners(still_mesh(&rig, report, mesh), points);
    FramingRequest rest_request;
    rest_request.up = o.up;
    const Framing rest_framing = frame_points(*points, rest_request);
    c.rest_radius = rest_framing.radius;
    points->clear();
    unweld(report, &mesh);
    for (int f : c.frames) {
        pose_mesh(rig, clip, clip_time(f / o.fps, duration, true), &mesh);
        add_corners(mesh, points);
    }
    return c;
}

// The file's other objects, as they come, and what the user should know of them.
void add_props(const LookRequest &o, const sim::MeshSpec &spec,
               const LookObjects &objects, const fs::path &dir, LookSetup *setup,
               const std::function<void(const std::string &)> &warn) {
    // The file's own floor, when one lies at the animal's feet, stands for the ground
    // (two coincident planes would flicker).
    const float radius = setup->framing.radius;
    for (const LookObject &p : objects.others) {
        // What the clip moves of the file's other objects (a rider, a harness, eyes)
        // plays it too.
        bool animated = false;
        if (!o.clip.empty()) {
            const Rig prop_rig = Rig::read(spec.path + "#" + p.name);
            animated = prop_rig.moves_mesh(prop_rig.clip(o.clip, "--clip"));
        }
        setup->props.push_back({p.name, mesh_reference(spec.path + "#" + p.name, dir),
                                p.materials, p.missing_texture.empty(), animated});
        if (!p.missing_texture.empty())
            warn(fmt::format("{}#{}: no image {}; its colours only", spec.path, p.name,
                             p.missing_texture));
        if (p.flat && p.flat_facing_up &&
            std::abs(p.flat_height - setup->framing.ground) <= 0.05 * radius)
            setup->ground = false;
    }
    std::string rest;
    for (const LookObject &p : objects.others)
        rest += (rest.empty() ? "\"" : ", \"") + p.name + "\"";
    warn(fmt::format(
        "{} holds {} objects; growing the pattern on \"{}\" (the largest "
        "that is not flat), the others ({}) in the file's materials; "
        "select another with {}#NAME",
        spec.path, objects.others.size() + 1, objects.animal, rest, spec.path));
    if (objects.left_out > 0)
        warn(
            fmt::format("{}: {} triangles belong to no object a name selects on its "
                        "own and are left out",
                        spec.path, objects.left_out));
}

}  // namespace

LookPlan plan_look(const LookRequest &o,
                   const std::function<void(const std::string &)> &warn) {
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
    // A bad preset fails here; one with an anisotropy field combs the fur along it.
    const bool preset_field =
        sim::load_preset(o.preset, o.presets_dir).params.anisotropy_field.kind !=
        sim::FieldSpec::Kind::none;
    // A file of several objects: the pattern goes on the animal, the rest as they come.
    LookObjects objects;
    if (!procedural && spec.object.empty()) {
        const double up_d[3] = {o.up.x, o.up.y, o.up.z};
        objects = choose_look_objects(spec.path, up_d);
    }
    const std::string grown_on =
        objects.animal.empty() ? o.mesh : spec.path + "#" + objects.animal;
    sim::MeshLoadReport report;
    const sim::TriangleMesh mesh = sim::load_mesh(grown_on, &report);
    // What a still shows, and what the facing is judged on: a skinned file in its
    // default pose (its bind space may lie in other units and axes).
    std::optional<Rig> rig;
    if (report.read.skinned_pieces > 0) rig = Rig::read(grown_on, Rig::Clips::optional);
    const sim::TriangleMesh shown = still_mesh(rig ? &*rig : nullptr, report, mesh);
    std::vector<Vec3f> points;
    ClipPoses clip;
    if (!o.clip.empty()) {
        clip = pose_clip(o, grown_on, report, mesh, &points);
    } else {
        if (!o.frames.empty())
            throw InputError("", 0, "--frames", "needs --clip (the animation to play)");
        if (o.shutter > 0)
            throw InputError("", 0, "--shutter", "needs --clip (the animation to blur)");
        add_corners(shown, &points);  // the camera frames what the still shows
    }

    LookPlan plan;
    LookSetup &setup = plan.setup;
    FramingRequest framing;
    framing.up = o.up;
    framing.aspect = float(o.width) / float(o.height);
    const BodyFacing facing = mesh_facing(shown, procedural ? "" : spec.path, o.up);
    framing.long_axis = facing.long_axis;
    framing.side_axis = facing.side_axis;
    setup.framing = frame_points(points, framing);
    setup.up = o.up;
    // A frame token before the extension (fox.####.exr, fox.%04d.exr) names the frames
    // as `pelage render -o` takes it; the pattern, the scene and the preview are named
    // after the text before it.
    std::string stem = output.stem().string(), token;
    if (const size_t dot = stem.rfind('.');
        dot != std::string::npos && has_frame_token(stem.substr(dot + 1))) {
        token = stem.substr(dot);
        stem.resize(dot);
    }
    setup.mesh = mesh_reference(grown_on, dir);
    if (!objects.animal.empty()) {
        setup.object_name = objects.animal;
        add_props(o, spec, objects, dir, &setup, warn);
    }
    setup.cells = stem + ".cells";
    setup.output = output.filename().string();
    setup.preview = stem + "_preview" + token + ".png";
    if (!o.clip.empty()) {
        // One image per frame: the frame number before the extension.
        if (token.empty()) {
            setup.output = stem + ".####.exr";
            setup.preview = stem + "_preview.####.png";
        }
        setup.clip = o.clip;
        setup.frames = std::max(clip.frames.back(), clip.last_frame) + 1;
        setup.fps = o.fps;
        setup.shutter = o.shutter;
        setup.body_radius = clip.rest_radius;
        plan.render_frames =
            o.frames.empty() ? "0-" + std::to_string(clip.frames.back()) : o.frames;
    }
    if (!procedural && objects.animal.empty()) setup.object_name = animal;
    setup.preset = o.preset;
    setup.seed = o.seed;
    setup.width = o.width;
    setup.height = o.height;
    setup.spp = o.spp;
    setup.view = o.view;
    setup.fur = o.fur;
    setup.denoise = o.denoise;
    setup.comb_field = preset_field;
    plan.scene_path = dir / (stem + ".json");
    return plan;
}

}  // namespace pelage::renderer
