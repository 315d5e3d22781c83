// Unidirectional path tracing with next-event estimation and multiple importance
// sampling (Veach 1997, PhD thesis, ch. 9, power heuristic β = 2): at every surface
// vertex one light is chosen by power and sampled (shadow ray by rtcOccluded1), and the
// BSDF is sampled to continue the path; emitters hit by BSDF-sampled rays are weighted
// against the light sampling density. Russian roulette from rr_depth on, with
// continuation probability min(0.95, max(β)).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "renderer/camera/camera.h"
#include "renderer/core/sampler.h"
#include "renderer/geometry/packet_intersect.h"
#include "renderer/image/film.h"
#include "renderer/image/filters.h"
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
    // README ("plugin_seconds"), checked by `pelage bench render`.
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

class PathIntegrator {
  public:
    PathIntegrator(const Scene &scene, const Camera &camera, const PixelFilter &filter,
                   int width, int height);

    // Adds samples [s0, s1) of every pixel in [x0, x1) × [y0, y1) to the film. Sample 0
    // also sets the pixel's point AOVs. `log`, when given, receives every ray cast.
    void render_tile(Film &film, Sampler &sampler, int x0, int y0, int x1, int y1, int s0,
                     int s1, RenderStats &stats, std::vector<RecordedRay> *log) const;

    // Camera motion blur: each sample draws a shutter position u in [0, 1) (one sampler
    // dimension after the lens) and traces from motion(u). Unset: the fixed camera.
    void set_camera_motion(std::function<Camera(float)> motion) {
        m_motion = std::move(motion);
    }
    // Time 1 plugin call in `stride` (default 16); 1 times every call (validation of the
    // extrapolated plugin_seconds by `pelage bench render`).
    void set_plugin_timing_stride(uint64_t stride) {
        m_plugin_timing_stride = std::max<uint64_t>(1, stride);
    }

  private:
    // The path from camera ray `cam`, whose first hit (traced in a packet by
    // render_tile) is `first`.
    Rgb radiance(const CameraRay &cam, const RTCRayHit &first, Sampler &sampler,
                 FilmSample &fs, FilmPointAovs *aovs, RenderStats &stats,
                 std::vector<RecordedRay> *log) const;

    const Scene &m_scene;
    const Camera &m_camera;
    const PixelFilter &m_filter;
    RTCScene m_rtc;
    PacketIntersector m_packets;  // camera rays
    int m_max_depth, m_rr_depth;
    int m_spp;             // samples per pixel: how much a rough bounce widens a cone
    float m_pixel_spread;  // the camera rays' cone, radians: a pixel's share per sample
                           // (ray_cone.h)
    double m_timer_overhead;
    uint64_t m_plugin_timing_stride = 16;
    std::function<Camera(float)> m_motion;
};

}  // namespace pelage::renderer
