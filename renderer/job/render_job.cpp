#include "renderer/job/render_job.h"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "renderer/core/progress.h"
#include "renderer/denoise/denoise.h"
#include "renderer/image/frame_pattern.h"
#include "renderer/integrator/render.h"
#include "renderer/job/frame_output.h"
#include "renderer/job/frame_resume.h"
#include "renderer/job/input_hash.h"
#include "renderer/job/render_plan.h"
#include "renderer/job/scene_patterns.h"
#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

class Timer {
  public:
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start)
            .count();
    }

  private:
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

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

// What every frame of one run shares.
struct JobContext {
    const RenderJob &job;
    const SceneDesc &desc;  // the job's changes applied
    const RenderPlan &plan;
    const PluginRegistry &plugins;
    const Scene *shared_scene;
    RenderObserver &observer;
};

enum class FrameOutcome {
    written,  // rendered (whole, or a still stopped by the cancel flag) and written
    skipped,  // resume found it complete
    aborted,  // a range interrupted mid-frame: nothing written, resume redoes it
};

// The render options of frame `local` (counted from the animation's first frame).
RenderOptions frame_options(const JobContext &c, const SceneDesc &fd, int local) {
    RenderOptions ro;
    ro.seed = c.job.seed;
    ro.frame = uint32_t(local);
    ro.cancel = c.job.cancel;
    ro.progress = c.job.progress;
    ro.camera = fd.camera;
    ro.instrument = c.job.instrument;  // plugin_seconds
    const auto &tt = c.desc.animation.turntable;
    if (tt && tt->target == TurntableDesc::Target::camera &&
        c.desc.animation.motion_blur()) {
        const double open = local + double(c.desc.animation.shutter_open),
                     span = double(c.desc.animation.shutter_close) -
                            double(c.desc.animation.shutter_open);
        ro.camera_motion = CameraMotion{&c.desc, open, span};
    }
    if (c.plan.tile)
        ro.region =
            RenderOptions::Region{0, c.plan.tile_y0, fd.film.width, c.plan.tile_y1};
    return ro;
}

// What a frame that builds its own scene (a clip, a deformation, growth) cost, frame by
// frame: the pose and its fur.
void add_own_scene_stats(const Scene &own, double setup_seconds, nlohmann::json *stat) {
    (*stat)["setup_seconds"] = setup_seconds;
    (*stat)["pose_seconds"] = own.geometry().pose_seconds();
    if (own.fur()) {
        (*stat)["fur_strands"] = own.fur()->num_strands();
        (*stat)["fur_grow_seconds"] = own.fur()->grow_seconds();
        (*stat)["fur_embree_seconds"] = own.fur()->embree_seconds();
    }
    (*stat)["peak_rss_mb"] = peak_rss_mb();  // of the process so far
}

// Frame f: rendered (the cancel flag stops it at the next tile and keeps what is done),
// then its EXR and preview written atomically.
FrameOutcome render_frame(const JobContext &c, int f, RenderTotals *totals) {
    FrameFiles files;
    files.frame = f;
    files.exr = substitute_frame(c.plan.output, f);
    files.preview = c.plan.preview.empty() ? "" : substitute_frame(c.plan.preview, f);
    files.settings = frame_settings_hash(c.plan.settings, f);
    if (c.job.resume) {
        std::string why;
        if (frame_is_done(files.exr, files.settings, c.plan, &why)) {
            ++totals->skipped;
            c.observer.info(files.exr + ": complete, skipped");
            return FrameOutcome::skipped;
        }
        if (why != "no file")
            c.observer.info(files.exr + ": " + why + ", rendering again");
    }
    // Motion, poses and random numbers follow the frame's place in the animation, so
    // animation.first_frame renumbers the frames without changing them.
    const int local = f - c.desc.animation.first_frame;
    const SceneDesc fd =
        c.desc.animation.present ? scene_at_frame(c.desc, local) : c.desc;
    std::unique_ptr<Scene> own;
    double frame_setup_seconds = 0;
    if (!c.shared_scene) {
        const Timer setup;
        own = std::make_unique<Scene>(fd, c.plugins);
        frame_setup_seconds = setup.seconds();
        totals->setup_seconds += frame_setup_seconds;
    }
    const Scene &scene = c.shared_scene ? *c.shared_scene : *own;

    const RenderResult r = render(scene, frame_options(c, fd, local));
    if (r.interrupted && c.plan.animated) {
        c.observer.warning("interrupted during frame " + std::to_string(f) + "; " +
                           files.exr + " not written");
        totals->aborted = true;
        return FrameOutcome::aborted;
    }

    std::vector<float> denoised;
    double denoise_seconds = 0;
    if (fd.film.denoise) {
        const Timer denoising;
        DenoiseStats ds;
        denoised = denoise(r.film->resolve_halves(), DenoiseOptions{}, &ds);
        denoise_seconds = denoising.seconds();
        totals->denoise_seconds += denoise_seconds;
        if (ds.pixels_passed_through > 0)
            c.observer.warning(fmt::format(
                "{}: {} pixels kept noisy in the denoised layer: {}", files.exr,
                ds.pixels_passed_through,
                r.spp_done < 2 ? "the denoiser needs 2 samples per pixel or more"
                               : "they hold no samples or non-finite values"));
    }
    const Timer writing;
    write_frame(
        r, scene, fd, c.desc, c.plan, files, c.job.seed,
        [&](const std::string &w) { c.observer.warning(w); }, denoised);
    totals->write_seconds += writing.seconds();
    ++totals->rendered;
    totals->stats.add(r.stats);
    totals->seconds += r.seconds;
    nlohmann::json frame_stat = {
        {"frame", f}, {"seconds", r.seconds}, {"output", files.exr}};
    if (fd.film.denoise) frame_stat["denoise_seconds"] = denoise_seconds;
    if (own) add_own_scene_stats(*own, frame_setup_seconds, &frame_stat);
    totals->frame_stats.push_back(frame_stat);

    FrameReport report;
    report.frame = f;
    report.output = files.exr;
    report.width = fd.film.width;
    report.height = fd.film.height;
    report.tile = c.plan.tile ? c.plan.tile->label() : "";
    report.spp = r.spp_done;
    report.adaptive = fd.film.noise_threshold > 0;
    report.mean_spp = double(r.stats.samples) / (double(fd.film.width) * fd.film.height);
    report.seconds = r.seconds;
    report.rays_per_second = r.seconds > 0 ? double(r.stats.rays()) / r.seconds : 0.0;
    report.nonfinite_samples = r.stats.nonfinite_samples;
    c.observer.frame_written(report);
    totals->spp_done = std::min(totals->spp_done, r.spp_done);
    if (r.interrupted) {
        c.observer.warning("interrupted; wrote " + files.exr + " with " +
                           std::to_string(r.spp_done) +
                           " samples in every pixel (more in some)");
        totals->interrupted = true;
    }
    return FrameOutcome::written;
}

RenderJob job_of(SceneDesc desc, std::string text) {
    RenderJob job;
    job.scene = std::move(desc);
    job.scene_text = std::move(text);
    return job;
}

}  // namespace

RenderJob render_job_from_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open scene file");
    std::ostringstream text;
    text << in.rdbuf();
    return render_job_from_text(text.str(), path);
}

RenderJob render_job_from_text(const std::string &text, const std::string &path) {
    return job_of(parse_scene(text, path), text);
}

RenderTotals run_render_job(const RenderJob &job, RenderObserver &observer) {
    const Timer wall;
    SceneDesc desc = job.scene;
    RenderPlan plan = plan_render(job, desc);
    // After the outputs are checked: a bad -o fails before a long growth. Its bar shows
    // where the render's does.
    grow_scene_patterns(
        desc, [&](const std::string &line) { observer.note(line); }, job.progress);
    const PluginRegistry plugins;
    plan.settings =
        settings_hash(desc, job.scene_text, plugins, job.seed, PELAGE_VERSION);
    const std::unique_ptr<Scene> shared_scene = shared_scene_for(desc, plugins);

    RenderTotals totals;
    totals.setup_seconds = wall.seconds();
    totals.spp_done = desc.film.spp;
    totals.width = desc.film.width;
    totals.height = desc.film.height;
    totals.animated = plan.animated;
    totals.first_output = substitute_frame(plan.output, plan.frames.front());
    if (plan.tile) totals.tile = plan.tile->label();
    if (shared_scene) {
        totals.shared_scene = true;
        totals.triangles = shared_scene->geometry().num_triangles();
        if (const FurGeometry *fur = shared_scene->fur()) {
            totals.has_fur = true;
            totals.fur_strands = fur->num_strands();
            totals.fur_grow_seconds = fur->grow_seconds();
            totals.fur_embree_seconds = fur->embree_seconds();
        }
    }
    std::optional<InterruptGuard> guard;
    RenderJob run = job;
    if (job.ctrl_c_stops) {
        guard.emplace();
        run.cancel = &InterruptGuard::flag();
    }
    const JobContext context{run, desc, plan, plugins, shared_scene.get(), observer};
    for (const int f : plan.frames) {
        if (render_frame(context, f, &totals) == FrameOutcome::aborted) break;
        if (totals.interrupted) break;
    }
    totals.wall_seconds = wall.seconds();
    return totals;
}

nlohmann::json render_stats_json(const RenderJob &job, const RenderTotals &totals) {
    const double rays_per_second =
        totals.seconds > 0 ? double(totals.stats.rays()) / totals.seconds : 0.0;
    nlohmann::json j = {{"seconds", totals.seconds},
                        {"wall_seconds", totals.wall_seconds},
                        {"setup_seconds", totals.setup_seconds},
                        {"write_seconds", totals.write_seconds},
                        {"denoise_seconds", totals.denoise_seconds},
                        {"spp", totals.spp_done},
                        {"width", totals.width},
                        {"height", totals.height},
                        {"rays", totals.stats.rays()},
                        {"rays_per_second", rays_per_second},
                        {"plugin_seconds", totals.stats.plugin_seconds()},
                        {"camera_rays", totals.stats.camera_rays},
                        {"secondary_rays", totals.stats.secondary_rays},
                        {"shadow_rays", totals.stats.shadow_rays},
                        {"samples", totals.stats.samples},
                        {"nonfinite_samples", totals.stats.nonfinite_samples},
                        {"plugin_calls", totals.stats.plugin_calls},
                        {"seed", job.seed},
                        {"interrupted", totals.interrupted},
                        {"output", totals.first_output}};
    if (totals.shared_scene) j["triangles"] = totals.triangles;
    if (totals.has_fur) {  // fur (docs/guide/fur.md)
        j["fur_strands"] = totals.fur_strands;
        j["fur_grow_seconds"] = totals.fur_grow_seconds;
        j["fur_embree_seconds"] = totals.fur_embree_seconds;
    }
    if (!totals.tile.empty()) j["tile"] = totals.tile;
    if (totals.animated) {
        j["frames"] = totals.frame_stats;
        j["frames_rendered"] = totals.rendered;
        j["frames_skipped"] = totals.skipped;
    }
    return j;
}

}  // namespace pelage::renderer
