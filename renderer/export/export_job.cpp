#include "renderer/export/export_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "pattern/bake/bake.h"
#include "renderer/export/coat.h"
#include "renderer/export/texture_png.h"
#include "renderer/export/usd_export.h"
#include "renderer/export/usda_writer.h"
#include "renderer/image/image_output.h"
#include "renderer/job/frame_list.h"
#include "renderer/job/scene_patterns.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

bool ends_with(const std::string &s, const std::string &tail) {
    return s.size() >= tail.size() &&
           s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Whether anything but the camera moves: then each frame's coat differs.
bool objects_move(const SceneDesc &d) {
    if (!d.animation.present) return false;
    for (const ObjectDesc &o : d.objects)
        if (!o.deform.empty() || o.grow || o.clip) return true;
    const auto &tt = d.animation.turntable;
    return tt && tt->target == TurntableDesc::Target::object;
}

std::vector<int> export_frames(const ExportJob &job) {
    const AnimationDesc &a = job.scene.animation;
    if (job.frames.empty()) {
        if (!objects_move(job.scene)) return {a.first_frame};
        std::vector<int> all;
        for (int f = 0; f < a.frames; ++f) all.push_back(a.first_frame + f);
        return all;
    }
    if (!a.present)
        throw InputError(job.scene.path, 0, "--frames",
                         "the scene has no animation; export it without --frames");
    const std::vector<int> frames = expand_frames(parse_frame_ranges(job.frames));
    for (int f : frames)
        if (f < a.first_frame || f >= a.first_frame + a.frames)
            throw InputError("", 0, "--frames",
                             "frame " + std::to_string(f) +
                                 " is outside the animation (" +
                                 std::to_string(a.first_frame) + "-" +
                                 std::to_string(a.first_frame + a.frames - 1) + ")");
    return frames;
}

struct Texture {
    std::vector<float> uvs;  // 6 per triangle
    std::string path;        // written
};

// The skin's pattern baked (pattern/bake): into the mesh's own UVs when they lie in
// one tile (0-1), else into an atlas of the surface.
Texture bake_skin_texture(const Scene &scene, const CoatSkin &skin, int size,
                          const std::string &path) {
    const ObjectDesc &od = scene.desc().objects[skin.object];
    if (od.cells.empty())
        throw InputError(scene.desc().path, 0, "--texture",
                         "object \"" + skin.name +
                             "\" has no .cells file: only a mosaic's pattern is baked");
    const MeshData &m = *scene.geometry().objects()[skin.object].mesh;
    sim::TriangleMesh rest;
    rest.positions.resize(m.rest->positions.size() / 3);
    for (size_t v = 0; v < rest.positions.size(); ++v)
        rest.positions[v] = {m.rest->positions[3 * v], m.rest->positions[3 * v + 1],
                             m.rest->positions[3 * v + 2]};
    rest.triangles.resize(m.num_triangles);
    for (size_t t = 0; t < m.num_triangles; ++t)
        for (int c = 0; c < 3; ++c)
            rest.triangles[t][size_t(c)] = m.triangles[3 * t + size_t(c)];
    const pattern::mosaic::MosaicPattern pattern(od.cells, rest, od.mesh);
    Texture tex;
    std::vector<float> pixels;
    bool own_uvs = !skin.uvs.empty();
    std::vector<sim::Vec2d> uvs;
    if (own_uvs) {
        for (size_t i = 0; i + 1 < skin.uvs.size(); i += 2)
            uvs.push_back({skin.uvs[i], skin.uvs[i + 1]});
        try {
            own_uvs = pattern::bake::udim_tiles(rest, uvs) == std::vector<int>{1001};
        } catch (const std::invalid_argument &) {
            own_uvs = false;
        }
    }
    if (own_uvs) {
        pattern::bake::BakeLayout layout;
        layout.mesh = &rest;
        layout.corner_uvs = uvs;
        layout.transfer = pattern.transfer();
        layout.width = layout.height = size;
        pattern::bake::BakeResult r = pattern::bake::bake_layout(pattern, layout);
        pixels = std::move(r.tiles.at(0).pixels);
        tex.uvs = skin.uvs;
    } else {
        std::optional<sim::Surface> render;
        if (pattern.transfer()) render = sim::build_surface(rest);
        std::optional<pattern::bake::BakedAtlas> baked;
        try {
            baked = pattern::bake::bake_atlas(pattern, size, size, 4,
                                              render ? &*render : nullptr);
        } catch (const std::invalid_argument &e) {
            std::string why =
                e.what();  // names bake's --res: this command's is --texture
            if (const size_t at = why.find("; raise --res"); at != std::string::npos)
                why.erase(at);
            throw InputError("", 0, "--texture",
                             std::to_string(size) + ": " + why + "; raise --texture");
        }
        pattern::bake::BakedAtlas &a = *baked;
        if (a.atlas.num_charts == 0 || skin.num_triangles() != m.num_triangles)
            throw std::runtime_error("the atlas does not cover the skin");
        tex.uvs.resize(6 * skin.num_triangles());
        for (size_t t = 0; t < skin.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c) {
                const sim::Vec2d uv = a.atlas.uv(sim::TriId(t), c);
                tex.uvs[6 * t + 2 * size_t(c)] = float(uv.x);
                tex.uvs[6 * t + 2 * size_t(c) + 1] = float(uv.y);
            }
        pixels = std::move(a.image.tiles.at(0).pixels);
    }
    const std::vector<unsigned char> rgb = srgb_rgb8(
        pixels, pattern::bake::BakeResult::channels, size_t(size) * size_t(size));
    write_rgb8(path, size, size, rgb);
    tex.path = path;
    return tex;
}

}  // namespace

void check_export_output(const ExportJob &job) {
    if (!ends_with(job.output, ".usda"))
        throw InputError(
            "", 0, job.output_flag,
            "\"" + job.output + "\": the coat is written as OpenUSD text (.usda)");
    const fs::path out_path(job.output);
    const fs::path folder = out_path.has_parent_path() ? out_path.parent_path() : ".";
    if (!fs::is_directory(folder))
        throw InputError(
            "", 0, job.output_flag,
            "\"" + job.output + "\": the folder " + folder.string() + " does not exist");
}

ExportReport run_export(const ExportJob &job,
                        const std::function<void(const std::string &)> &note) {
    check_export_output(job);
    const fs::path out_path(job.output);
    const fs::path folder = out_path.has_parent_path() ? out_path.parent_path() : ".";
    const SceneDesc &desc = job.scene;
    ExportReport report;
    report.frames = export_frames(job);
    const bool animated = report.frames.size() > 1 || !job.frames.empty();
    const auto setup_start = Clock::now();
    grow_scene_patterns(
        desc, note ? note : [](const std::string &) {}, false);
    // Without fur in the export, none is grown.
    SceneDesc bare;
    if (!job.fur) {
        bare = desc;
        for (ObjectDesc &o : bare.objects) o.fur.reset();
    }
    const SceneDesc &source = job.fur ? desc : bare;
    const PluginRegistry plugins;
    CoatOptions options;
    options.objects = job.objects;
    options.fur = job.fur;

    std::vector<CoatFrame> coat;
    std::vector<Texture> textures;
    double gather_seconds = 0;
    try {
        for (size_t k = 0; k < report.frames.size(); ++k) {
            const int local = report.frames[k] - desc.animation.first_frame;
            const SceneDesc fd = animated ? scene_at_frame(source, local) : source;
            const Scene scene(fd, plugins);
            const auto gather_start = Clock::now();
            coat.push_back(gather_coat(scene, options));
            const uint64_t points =
                uint64_t(coat.back().num_points()) * uint64_t(report.frames.size());
            if (points > job.max_points)
                throw InputError(
                    desc.path, 0, "--max-points",
                    "the export would hold " + std::to_string(points) +
                        " control points over " + std::to_string(report.frames.size()) +
                        " frames (at most " + std::to_string(job.max_points) +
                        "); export fewer frames (--frames), lower the fur's "
                        "density, or raise --max-points");
            if (k == 0 && job.texture_size > 0) {
                const auto bake_start = Clock::now();
                const std::string stem = out_path.stem().string();
                for (CoatSkin &skin : coat[0].skins) {
                    const std::string name =
                        stem + "_" + usd_identifier(skin.name) + ".png";
                    textures.push_back(bake_skin_texture(scene, skin, job.texture_size,
                                                         (folder / name).string()));
                    report.files.push_back(textures.back().path);
                    skin.texture = "./" + name;
                }
                report.texture_seconds = since(bake_start);
            }
            if (!textures.empty())
                for (size_t s = 0; s < coat.back().skins.size(); ++s) {
                    coat.back().skins[s].uvs = textures[s].uvs;
                    coat.back().skins[s].texture = coat[0].skins[s].texture;
                }
            gather_seconds += since(gather_start);
        }
        gather_seconds -= report.texture_seconds;
        report.setup_seconds =
            since(setup_start) - gather_seconds - report.texture_seconds;

        const auto write_start = Clock::now();
        UsdStageInfo info;
        const Vec3f up = desc.camera.up;
        info.up_axis = std::abs(up.z) > std::abs(up.y) ? 'Z' : 'Y';
        info.meters_per_unit = job.meters_per_unit;
        info.fps = desc.animation.fps;
        for (int f : report.frames) info.times.push_back(double(f));
        info.doc = job.command;
        write_file_atomically(
            job.output, [&](std::ostream &out) { write_coat_usda(out, coat, info); });
        report.write_seconds = gather_seconds + since(write_start);
    } catch (...) {
        std::error_code ec;
        for (const Texture &t : textures) fs::remove(t.path, ec);
        throw;
    }
    report.files.insert(report.files.begin(), job.output);
    report.bytes = fs::file_size(job.output);
    report.skins = coat[0].skins.size();
    for (const CoatSkin &s : coat[0].skins) report.triangles += s.num_triangles();
    report.strands = coat[0].num_strands();
    report.points = coat[0].num_points();
    return report;
}

}  // namespace pelage::renderer
