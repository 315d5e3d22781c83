#include "renderer/integrator/instrumentation.h"

namespace pelage::renderer {

double timer_overhead_seconds() {
    static const double overhead = [] {
        double best = 1e9;
        for (int i = 0; i < 2000; ++i) {
            const auto a = std::chrono::steady_clock::now();
            const auto b = std::chrono::steady_clock::now();
            best = std::min(best, std::chrono::duration<double>(b - a).count());
        }
        return best;
    }();
    return overhead;
}

void RenderStats::add(const RenderStats &o) {
    camera_rays += o.camera_rays;
    secondary_rays += o.secondary_rays;
    shadow_rays += o.shadow_rays;
    samples += o.samples;
    nonfinite_samples += o.nonfinite_samples;
    plugin_calls += o.plugin_calls;
    plugin_timed_calls += o.plugin_timed_calls;
    plugin_timed_seconds += o.plugin_timed_seconds;
}

}  // namespace pelage::renderer
