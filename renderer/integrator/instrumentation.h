// The path integrator's statistics, and its benchmark instrumentation as a compile-time
// policy. The integrator is a template on the policy: production renders use
// NoInstrumentation, whose hooks are empty inline functions, so that instantiation
// holds no clock reads, no ray log and no branch on either; `pelage bench render` and
// `pelage render --stats-json` use Instrumented.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/scene/scene.h"

namespace pelage::renderer {

struct RenderStats {
    uint64_t camera_rays = 0, secondary_rays = 0, shadow_rays = 0;
    uint64_t samples = 0, nonfinite_samples = 0;
    uint64_t plugin_calls = 0, plugin_timed_calls = 0;
    double plugin_timed_seconds = 0;  // over the timed subset of calls

    uint64_t rays() const { return camera_rays + secondary_rays + shadow_rays; }
    // Time in plugins: the mean of the timed 1-in-16 subset (timing every call would
    // cost more than the calls) times all calls, less the clock reads' own cost; timed
    // calls longer than 100 µs (preempted) are left out of the mean. Accuracy: see
    // README ("plugin_seconds"), checked by `pelage bench render`. Zero unless the
    // render is instrumented.
    double plugin_seconds() const {
        return plugin_timed_calls
                   ? plugin_timed_seconds * double(plugin_calls) / plugin_timed_calls
                   : 0.0;
    }
    void add(const RenderStats &o);
};

// For `pelage bench render`: every ray the tracer casts, to replay it through raw Embree.
struct RecordedRay {
    float o[3], tfar;
    float d[3];
    uint32_t kind;  // 0 camera, 1 secondary, 2 shadow
};

enum RayKind : uint32_t { camera_ray = 0, secondary_ray = 1, shadow_ray = 2 };

// Production: the material plugin is called and counted, nothing else.
struct NoInstrumentation {
    void ray(Vec3f, Vec3f, float, RayKind) const {}
    void shade(const Material &mat, const PelageHit &hit, PelageShade &sh,
               RenderStats &stats) const {
        ++stats.plugin_calls;
        mat.plugin->shade(mat.instance, &hit, &sh);
    }
};

// The cost of the two clock reads around a timed plugin call (the fastest of many
// back-to-back pairs), subtracted from each timing: in a VM a clock read can cost more
// than a simple plugin.
double timer_overhead_seconds();

// Benchmarks: times 1 plugin call in `stride` (1: every call, to validate the
// extrapolated plugin_seconds) and appends every ray cast to `log` when given. One per
// thread (the log is the thread's).
struct Instrumented {
    std::vector<RecordedRay> *log = nullptr;
    uint64_t stride = 16;
    double timer_overhead = 0;  // timer_overhead_seconds()

    // A call that took longer than this was preempted (the thread lost its core); one
    // such sample, extrapolated 16×, would dominate the estimate on a shared machine. It
    // is left out of the mean, not counted as shading.
    static constexpr double max_plugin_call_seconds = 100e-6;

    void ray(Vec3f o, Vec3f d, float tfar, RayKind kind) const {
        if (log) log->push_back({{o.x, o.y, o.z}, tfar, {d.x, d.y, d.z}, kind});
    }
    void shade(const Material &mat, const PelageHit &hit, PelageShade &sh,
               RenderStats &stats) const {
        if (stats.plugin_calls++ % stride != 0) {
            mat.plugin->shade(mat.instance, &hit, &sh);
            return;
        }
        const auto t0 = std::chrono::steady_clock::now();
        mat.plugin->shade(mat.instance, &hit, &sh);
        const double dt =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (dt < max_plugin_call_seconds) {
            stats.plugin_timed_seconds += std::max(0.0, dt - timer_overhead);
            ++stats.plugin_timed_calls;
        }
    }
};

}  // namespace pelage::renderer
