// Unidirectional path tracing with next-event estimation and multiple importance
// sampling (Veach 1997, PhD thesis, ch. 9, power heuristic β = 2): at every surface
// vertex one light is chosen by power and sampled (shadow ray by rtcOccluded1), and the
// BSDF is sampled to continue the path; emitters hit by BSDF-sampled rays are weighted
// against the light sampling density. Russian roulette from rr_depth on, with
// continuation probability min(0.95, max(β)).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "renderer/camera/camera.h"
#include "renderer/core/sampler.h"
#include "renderer/geometry/packet_intersect.h"
#include "renderer/image/film.h"
#include "renderer/image/filters.h"
#include "renderer/integrator/instrumentation.h"
#include "renderer/scene/scene.h"

namespace pelage::renderer {

class PathIntegrator {
  public:
    PathIntegrator(const Scene &scene, const Camera &camera, const PixelFilter &filter,
                   int width, int height);

    // Adds samples [s0, s1) of every pixel in [x0, x1) × [y0, y1) to the film, or only
    // of those whose `active` flag (one byte per image pixel, row-major) is set. Sample 0
    // also sets the pixel's point AOVs. `instr`: NoInstrumentation or Instrumented
    // (instrumentation.h).
    template <typename Instr>
    void render_tile(Film &film, Sampler &sampler, int x0, int y0, int x1, int y1, int s0,
                     int s1, RenderStats &stats, const Instr &instr,
                     const uint8_t *active = nullptr) const;

    // Camera motion blur: each sample draws a shutter position u in [0, 1) (one sampler
    // dimension after the lens) and traces from motion->at(u). Unset: the fixed camera.
    // Moving geometry (EmbreeScene::moves()) draws u the same way; its rays carry it as
    // their time. `motion` outlives the integrator.
    void set_camera_motion(const CameraMotion *motion) { m_motion = motion; }

  private:
    struct PathState;      // what a path carries from vertex to vertex
    struct SurfaceVertex;  // a hit on a mesh, before shading
    struct StrandVertex;   // a hit on a fur strand, in its fibre frame (integrator_fur.h)
    struct VertexSamples;  // the sampler dimensions a vertex consumes

    // The path from camera ray `cam`, whose first hit (traced in a packet by
    // render_tile) is `first`.
    template <typename Instr>
    Rgb radiance(const CameraRay &cam, float time, const RTCRayHit &first,
                 Sampler &sampler, FilmSample &fs, FilmPointAovs *aovs,
                 RenderStats &stats, const Instr &instr) const;

    // The steps of radiance(), in path order.
    template <typename Instr>
    RTCRayHit trace(PathState &path, RenderStats &stats, const Instr &instr) const;
    bool add_emission(const RTCRayHit &rh, int depth, const CameraRay &cam,
                      PathState &path, FilmSample &fs, FilmPointAovs *aovs) const;
    SurfaceVertex surface_vertex(const RTCRayHit &rh, PathState &path) const;
    template <typename Instr>
    PelageShade shade(const SurfaceVertex &sv, int depth, Rgb *albedo, RenderStats &stats,
                      const Instr &instr) const;
    void set_first_hit(const SurfaceVertex &sv, const PelageShade &sh, const Rgb &albedo,
                       const CameraRay &cam, FilmSample &fs, FilmPointAovs *aovs) const;
    template <typename Instr>
    bool scatter_at_surface(const SurfaceVertex &sv, const PelageShade &sh,
                            const Rgb &albedo, Sampler &sampler, PathState &path,
                            RenderStats &stats, const Instr &instr) const;
    template <typename Bsdf, typename Instr>
    bool scatter(const Bsdf &bsdf, const SurfaceVertex &sv, const VertexSamples &u,
                 PathState &path, RenderStats &stats, const Instr &instr) const;
    // The same steps at a fur strand (integrator_fur.cpp).
    // camera_hit: rh is the camera ray's, traced in the camera scene (FurGeometry).
    StrandVertex strand_vertex(const FurLayer &layer, const RTCRayHit &rh,
                               const PathState &path, bool camera_hit) const;
    void set_first_hit(const StrandVertex &v, const CameraRay &cam, FilmSample &fs,
                       FilmPointAovs *aovs) const;
    template <typename Instr>
    bool scatter_at_strand(const StrandVertex &v, Sampler &sampler, PathState &path,
                           RenderStats &stats, const Instr &instr) const;
    bool continue_path(int depth, Sampler &sampler, PathState &path) const;
    void set_matte_keys(const SurfaceVertex &sv, const PelageShade &sh,
                        FilmSample &fs) const;

    const Scene &m_scene;
    const Camera &m_camera;
    const PixelFilter &m_filter;
    RTCScene m_rtc;
    PacketIntersector m_packets;  // camera rays
    int m_width, m_height;
    int m_max_depth, m_rr_depth;
    float m_clamp_indirect;        // 0: off
    bool m_fur_far_field;          // IntegratorDesc::fur_far_field
    float m_fur_bounce_roughness;  // IntegratorDesc::fur_bounce_roughness
    int m_spp;             // samples per pixel: how much a rough bounce widens a cone
    float m_pixel_spread;  // the camera rays' cone, radians: a pixel's share per sample
                           // (ray_cone.h)
    float m_pixel_angle;   // a whole pixel's angle at the image centre, radians
    const CameraMotion *m_motion = nullptr;
    bool m_timed;  // the camera or geometry moves: each sample draws a shutter time
    int m_mattes;  // the film's Cryptomatte layers (Scene::matte_layers())
};

struct PathIntegrator::PathState {
    Rgb L{}, beta{1, 1, 1};
    Vec3f o, d;
    float prev_pdf = 0;  // solid-angle density of the BSDF sample that made d
    bool prev_specular = false;
    Vec3f prev_ng{0, 0, 1};  // geometric normal at the vertex d left
    float footprint = 0;     // ray cone width at the ray origin (ray_cone.h)
    float spread;            // ... and its full angle, radians
    unsigned fur_skip = 0;   // the strand the ray leaves, + 1 (fur_geometry.h)
    float time = 0;          // in the shutter, [0, 1): every ray of the path's
};

}  // namespace pelage::renderer
