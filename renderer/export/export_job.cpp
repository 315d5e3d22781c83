#include "renderer/export/export_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "renderer/export/coat.h"
#include "renderer/export/skin_texture.h"
#include "renderer/export/usd_export.h"
#include "renderer/export/usda_writer.h"
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
    std::vector<SkinTexture> textures;
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
        for (const SkinTexture &t : textures) fs::remove(t.path, ec);
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
