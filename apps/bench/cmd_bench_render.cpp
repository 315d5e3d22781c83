// `pelage bench render`: throughput of the full path tracer against raw Embree on the
// same rays. The tracer's rays (camera, secondary, shadow) are recorded in one 1-spp
// render, then replayed through rtcIntersect1 alone, one ray at a time (the `ratio`
// baseline). Also reported: the replay with the tracer's own calls (camera rays in the
// same packets, rtcOccluded1 for shadow rays: what Embree alone would take for the
// tracer's work), the 1 → N thread scaling, and plugin_seconds (1 call in 16 timed,
// extrapolated) against a render that times every plugin call.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <thread>

#include "apps/bench/bench.h"
#include "renderer/geometry/packet_intersect.h"
#include "renderer/integrator/render.h"
#include "renderer/job/scene_patterns.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

using namespace pelage::renderer;

struct BenchRenderOptions {
    std::string scene, res = "1280x720";
    int spp = 4, repeat = 3;
    BenchOutput out;
};

// Replays the recorded rays. Baseline: every ray through rtcIntersect1. Same calls: the
// calls the tracer made, runs of consecutive camera rays (a tile row's packet, as they
// were recorded) through the same PacketIntersector and shadow rays through
// rtcOccluded1.
double replay(RTCScene scene, const PacketIntersector &packets,
              const std::vector<std::vector<RecordedRay>> &logs, bool same_calls) {
    constexpr size_t block = 4096;
    std::vector<std::pair<const RecordedRay *, size_t>> blocks;
    for (const auto &l : logs)
        for (size_t i = 0; i < l.size(); i += block)
            blocks.emplace_back(l.data() + i, std::min(block, l.size() - i));
    const Timer t;
    tbb::parallel_for(size_t(0), blocks.size(), [&](size_t b) {
        const auto [rays, n] = blocks[b];
        for (size_t i = 0; i < n; ++i) {
            const RecordedRay &r = rays[i];
            if (same_calls && r.kind == 0) {
                constexpr int K = PacketIntersector::max_rays;
                Vec3f o[K], d[K];
                int m = 0;
                for (; m < K && i + m < n && rays[i + m].kind == 0; ++m) {
                    const RecordedRay &c = rays[i + m];
                    o[m] = {c.o[0], c.o[1], c.o[2]};
                    d[m] = {c.d[0], c.d[1], c.d[2]};
                }
                RTCRayHit hits[K];
                packets.intersect(o, d, m, hits);
                i += size_t(m) - 1;
                continue;
            }
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = r.kind == 0 ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                    : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
            RTCRayHit rh;
            rh.ray.org_x = r.o[0];
            rh.ray.org_y = r.o[1];
            rh.ray.org_z = r.o[2];
            rh.ray.tnear = 0;
            rh.ray.dir_x = r.d[0];
            rh.ray.dir_y = r.d[1];
            rh.ray.dir_z = r.d[2];
            rh.ray.time = 0;
            rh.ray.tfar = r.tfar;
            rh.ray.mask = 0xffffffffu;
            rh.ray.id = 0;
            rh.ray.flags = 0;
            if (same_calls && r.kind == 2) {
                rtcOccluded1(scene, &ctx, &rh.ray);
            } else {
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &ctx, &rh);
            }
        }
    });
    return t.seconds();
}

int run(const BenchRenderOptions &o) {
    const std::string path = o.scene.empty() ? data_path("scenes/cow.json") : o.scene;
    SceneDesc desc = load_scene_file(path);
    grow_scene_patterns(desc, false);
    parse_resolution(o.res, 16384, &desc.film.width, &desc.film.height);
    desc.film.spp = o.spp;
    const PluginRegistry plugins;
    const Scene scene(desc, plugins);
    const int cores = int(std::max(1u, std::thread::hardware_concurrency()));

    // --- The path tracer at 1 thread and at all cores (best of `repeat`) ---
    auto timed_render = [&](int threads) {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism,
                              size_t(threads));
        RenderResult best;
        double best_cpu = 0;
        for (int i = 0; i < o.repeat; ++i) {
            const double c0 = process_cpu_seconds();
            RenderOptions instrumented;
            instrumented.instrument = true;
            RenderResult r = render(scene, instrumented);
            const double cpu = process_cpu_seconds() - c0;
            if (i == 0 || r.seconds < best.seconds) best = std::move(r);
            if (i == 0 || cpu < best_cpu) best_cpu = cpu;
        }
        return std::make_pair(std::move(best), best_cpu);
    };
    const auto [r1, cpu1] = timed_render(1);
    const auto [rn, cpun] = timed_render(cores);
    const double pt_rays_per_second = double(rn.stats.rays()) / rn.seconds;

    // --- plugin_seconds: the 1-in-16 extrapolation against timing every call ---
    RenderOptions every_call;
    every_call.instrument = true;
    every_call.plugin_timing_stride = 1;
    const RenderResult timed_all = render(scene, every_call);

    // --- Record one 1-spp render's rays and replay them through raw Embree ---
    SceneDesc one = desc;
    one.film.spp = 1;
    const Scene scene1(one, plugins);
    RenderOptions rec;
    rec.instrument = true;
    rec.record_rays = true;
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(cores));
    const RenderResult recorded = render(scene1, rec);
    size_t recorded_rays = 0;
    for (const auto &l : recorded.rays) recorded_rays += l.size();
    const PacketIntersector packets(scene1.geometry().device(),
                                    scene1.geometry().scene());
    double t_intersect = 1e300, t_mixed = 1e300, cpu_intersect = 1e300;
    for (int i = 0; i < std::max(1, o.repeat); ++i) {
        const double c0 = process_cpu_seconds();
        t_intersect = std::min(t_intersect, replay(scene1.geometry().scene(), packets,
                                                   recorded.rays, false));
        cpu_intersect = std::min(cpu_intersect, process_cpu_seconds() - c0);
        t_mixed = std::min(
            t_mixed, replay(scene1.geometry().scene(), packets, recorded.rays, true));
    }
    const double embree_rps = recorded_rays / t_intersect,
                 mixed_rps = recorded_rays / t_mixed;
    const double pt_cpu_rps = double(rn.stats.rays()) / cpun;
    const double embree_cpu_rps = double(recorded_rays) / cpu_intersect;
    nlohmann::json j = {
        {"benchmark", "render"},
        {"scene", path},
        {"width", desc.film.width},
        {"height", desc.film.height},
        {"spp", o.spp},
        {"threads", cores},
        {"triangles", scene.geometry().num_triangles()},
        {"camera_packet_width", packets.width()},
        {"seconds", rn.seconds},
        {"seconds_1_thread", r1.seconds},
        {"rays", rn.stats.rays()},
        {"camera_rays", rn.stats.camera_rays},
        {"secondary_rays", rn.stats.secondary_rays},
        {"shadow_rays", rn.stats.shadow_rays},
        {"plugin_seconds", rn.stats.plugin_seconds()},
        {"plugin_seconds_every_call_timed", timed_all.stats.plugin_seconds()},
        {"plugin_seconds_extrapolation_error",
         timed_all.stats.plugin_seconds() > 0
             ? rn.stats.plugin_seconds() / timed_all.stats.plugin_seconds() - 1
             : 0.0},
        {"path_tracer_rays_per_second", pt_rays_per_second},
        {"path_tracer_rays_per_second_1_thread", double(r1.stats.rays()) / r1.seconds},
        {"embree_rays", recorded_rays},
        {"embree_rays_per_second", embree_rps},
        {"embree_same_calls_rays_per_second", mixed_rps},
        {"ratio", pt_rays_per_second / embree_rps},
        {"ratio_same_calls", pt_rays_per_second / mixed_rps},
        {"thread_scaling", r1.seconds / rn.seconds},
        {"path_tracer_rays_per_cpu_second", pt_cpu_rps},
        {"embree_rays_per_cpu_second", embree_cpu_rps},
        {"ratio_cpu", pt_cpu_rps / embree_cpu_rps},
        {"cpu_seconds", cpun},
        {"cpu_seconds_1_thread", cpu1},
    };
    o.out.emit(j);
    return 0;
}

}  // namespace

Runner add_bench_render(CLI::App &bench) {
    auto o = std::make_shared<BenchRenderOptions>();
    CLI::App *sub = bench.add_subcommand(
        "render", "Path tracer rays/s vs raw Embree on the same rays; thread scaling");
    sub->add_option("--scene", o->scene, "Scene file (default: scenes/cow.json)");
    sub->add_option("--res", o->res, "Resolution WIDTHxHEIGHT (default 1280x720)");
    sub->add_option("--spp", o->spp, "Samples per pixel of the timed renders (default 4)")
        ->check(CLI::Range(1, 4096));
    sub->add_option("--repeat", o->repeat,
                    "Runs per measurement (default 3); the fastest counts")
        ->check(CLI::Range(1, 100));
    o->out.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
