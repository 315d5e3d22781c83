#include "renderer/integrator/integrator_path.h"

#include <cmath>
#include <limits>
#include <utility>

#include "renderer/bsdf/bsdf_coated.h"
#include "renderer/bsdf/bsdf_lambert.h"
#include "renderer/core/ray_cone.h"
#include "renderer/core/sampling.h"
#include "renderer/geometry/embree_ray.h"
#include "renderer/integrator/integrator_fur.h"
#include "renderer/integrator/light_sampling.h"

namespace pelage::renderer {

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr int max_infinite_lights = 8;

// f and the BSDF's pdf for one direction pair, fused when the BSDF offers it.
template <typename B>
Rgb eval_with_pdf(const B &bsdf, Vec3f wo, Vec3f wi, float *pdf) {
    if constexpr (requires { bsdf.eval_pdf(wo, wi, pdf); }) {
        return bsdf.eval_pdf(wo, wi, pdf);
    } else {
        *pdf = bsdf.pdf(wo, wi);
        return bsdf.eval(wo, wi);
    }
}

// A surface vertex as sample_ld() sees it: light from above the geometric surface only;
// f and pdf from one fused evaluation where the BSDF offers it.
template <typename Bsdf>
struct SurfaceLdVertex {
    const Bsdf &bsdf;
    const Frame &frame;
    Vec3f wo_local, p, n;  // n: the geometric normal
    float time;
    static constexpr unsigned ray_id = 0;
    mutable float bsdf_pdf = 0;

    bool accepts(Vec3f wi) const { return dot(wi, n) > 0; }
    Vec3f to_local(Vec3f w) const { return frame.to_local(w); }
    Rgb f(Vec3f wi_local) const {
        return eval_with_pdf(bsdf, wo_local, wi_local, &bsdf_pdf);
    }
    float pdf(Vec3f) const { return bsdf_pdf; }
};

}  // namespace

PathIntegrator::PathIntegrator(const Scene &scene, const Camera &camera,
                               const PixelFilter &filter, int width, int height)
    : m_scene(scene),
      m_camera(camera),
      m_filter(filter),
      m_rtc(scene.geometry().scene()),
      m_packets(scene.geometry().device(), scene.fur() && scene.fur()->widened()
                                               ? scene.fur()->camera_scene()
                                               : scene.geometry().scene()),
      m_width(width),
      m_height(height),
      m_max_depth(scene.desc().integrator.max_depth),
      m_rr_depth(scene.desc().integrator.rr_depth),
      m_clamp_indirect(scene.desc().integrator.clamp_indirect),
      m_fur_far_field(scene.desc().integrator.fur_far_field),
      m_fur_bounce_roughness(scene.desc().integrator.fur_bounce_roughness),
      m_spp(scene.desc().film.spp),
      m_timed(scene.moves()),
      m_mattes(int(scene.matte_layers().size())) {
    m_pixel_angle =
        2 * std::tan(0.5f * scene.desc().camera.fov_deg * pi / 180) / float(height);
    m_pixel_spread = m_pixel_angle * camera_spread_scale(m_spp);
}

template <typename Instr>
void PathIntegrator::render_tile(Film &film, Sampler &sampler, int x0, int y0, int x1,
                                 int y1, int s0, int s1, RenderStats &stats,
                                 const Instr &instr, const uint8_t *active) const {
    constexpr int K = PacketIntersector::max_rays;
    Sampler lane[K];
    CameraRay cam[K];
    Vec3f org[K], dir[K];
    unsigned ids[K];
    float times[K];
    RTCRayHit first[K];
    // Widened fur: each camera ray brings a stratified number for its opacity
    // (fur_geometry.h), one more dimension of its sampler.
    const bool fur_xi = m_scene.fur() && m_scene.fur()->widened();
    // Row by row, sample by sample, K neighbouring pixels at a time: their camera rays
    // form one coherent packet. Each pixel still receives its samples in sample order.
    // The rows run back and forth (boustrophedon), so consecutive camera hits stay
    // neighbours where one row ends and the next begins: shaders that reuse the previous
    // hit's work (the clonal mosaic's CoherentLookup) reuse it there too. Pixels are
    // independent (own sampler, own film pixel), so the order changes no result.
    // The row's pixels still sampling (all of them unless adaptive sampling stopped
    // some), packed so packets stay full.
    std::vector<int> row;
    row.reserve(size_t(x1 - x0));
    int sweep = 0;
    for (int y = y0; y < y1; ++y) {
        row.clear();
        for (int x = x0; x < x1; ++x)
            if (!active || active[size_t(y) * size_t(m_width) + size_t(x)])
                row.push_back(x);
        const int count = int(row.size());
        const int packets = (count + K - 1) / K;
        for (int s = s0; s < s1; ++s, ++sweep)
            for (int p = 0; p < packets; ++p) {
                const bool backwards = sweep & 1;
                const int first_i = K * (backwards ? packets - 1 - p : p);
                const int n = std::min(K, count - first_i);
                const int *xs = &row[size_t(first_i)];
                // --- Camera rays, offsets drawn from the filter (every sample has
                // weight 1) ---
                for (int i = 0; i < n; ++i) {
                    Sampler &sp = lane[i];
                    sp = sampler;
                    sp.start_pixel_sample(uint32_t(xs[i]), uint32_t(y), uint32_t(s));
                    const auto [fu, fv] = sp.get_2d();
                    const float dx = m_filter.sample_1d(fu), dy = m_filter.sample_1d(fv);
                    // A pinhole draws no lens sample: one pair less per camera ray.
                    const bool timed = m_motion || m_timed;
                    const auto [lu, lv] = timed || m_camera.has_lens()
                                              ? sp.get_2d()
                                              : Sampler::Pair{0.5f, 0.5f};
                    const float px = float(xs[i]) + 0.5f + dx, py = float(y) + 0.5f + dy;
                    times[i] = timed ? sp.get_1d() : 0.0f;
                    cam[i] = m_motion ? m_motion->at(times[i], m_width, m_height)
                                            .generate(px, py, lu, lv)
                                      : m_camera.generate(px, py, lu, lv);
                    org[i] = cam[i].o;
                    dir[i] = cam[i].d;
                    ids[i] = fur_xi ? fur_ray_id(0, sp.get_1d()) : 0;
                }
                m_packets.intersect(org, dir, n, first, ids, m_timed ? times : nullptr);
                stats.camera_rays += uint64_t(n);
                for (int i = 0; i < n; ++i) instr.ray(org[i], dir[i], inf, camera_ray);
                // --- The paths, one pixel at a time ---
                for (int j = 0; j < n; ++j) {
                    const int i = backwards ? n - 1 - j : j, x = xs[i];
                    FilmSample fs;
                    FilmPointAovs aovs;
                    fs.L = radiance(cam[i], times[i], first[i], lane[i], fs,
                                    s == 0 ? &aovs : nullptr, stats, instr);
                    ++stats.samples;
                    if (s == 0) film.set_point_aovs(x, y, aovs);
                    // No NaN or Inf reaches the film: drop the sample and count it.
                    if (!is_finite(fs.L) || !is_finite(fs.albedo) ||
                        !is_finite(fs.normal)) {
                        ++stats.nonfinite_samples;
                        continue;
                    }
                    film.add(x, y, 1.0f, fs);
                    if (film.has_halves())
                        film.add_half(
                            x, y, uint32_t(s), fs,
                            first[i].hit.geomID != RTC_INVALID_GEOMETRY_ID
                                ? first[i].ray.tfar * dot(cam[i].d, cam[i].forward)
                                : inf);
                }
            }
    }
}

// --- The path ---

struct PathIntegrator::SurfaceVertex {
    uint32_t object, prim;
    float b0, b1, b2;  // barycentrics
    float t_hit;
    Vec3f p, ng, ns, wo;  // ng faces wo; ns faces wo and ng
    float footprint;      // the ray cone's width at the hit
};

// One 2D sample each, drawn in this order: the light and the BSDF lobe, the point on the
// light, the BSDF direction.
struct PathIntegrator::VertexSamples {
    Sampler::Pair pick, light, bsdf;
};

// pbrt-v4 §13.4 (PathIntegrator::Li): at each vertex, emission reached by the ray, then
// next-event estimation and BSDF sampling at a fur strand or a surface, then Russian
// roulette.
template <typename Instr>
Rgb PathIntegrator::radiance(const CameraRay &cam, float time, const RTCRayHit &first,
                             Sampler &sampler, FilmSample &fs, FilmPointAovs *aovs,
                             RenderStats &stats, const Instr &instr) const {
    PathState path{
        .o = cam.o, .d = cam.d, .spread = m_pixel_spread, .time = m_timed ? time : 0.0f};
    // Direct light at the first hit: its light samples and what its BSDF sample reaches
    // (clamp_indirect leaves it alone).
    Rgb direct{};
    bool clamp = false;
    for (int depth = 0;; ++depth) {
        const RTCRayHit rh = depth == 0 ? first : trace(path, stats, instr);
        const bool ends = add_emission(rh, depth, cam, path, fs, aovs);
        if (depth == 1 && m_clamp_indirect > 0) direct = path.L, clamp = true;
        if (ends) break;
        bool scattered;
        if (const FurLayer *layer =
                m_scene.fur() ? m_scene.fur()->layer_of(rh.hit.geomID) : nullptr) {
            const StrandVertex v = strand_vertex(*layer, rh, path, depth == 0);
            if (depth == 0) set_first_hit(v, cam, fs, aovs);
            scattered =
                depth < m_max_depth && scatter_at_strand(v, sampler, path, stats, instr);
        } else {
            const SurfaceVertex sv = surface_vertex(rh, path);
            Rgb albedo;
            const PelageShade sh = shade(sv, depth, &albedo, stats, instr);
            if (depth == 0) set_first_hit(sv, sh, albedo, cam, fs, aovs);
            scattered = depth < m_max_depth &&
                        scatter_at_surface(sv, sh, albedo, sampler, path, stats, instr);
        }
        // What the first hit's light samples added (scatter adds them to L before
        // the BSDF's ray is traced), with what the camera ray saw of a light.
        if (depth == 0) fs.direct = path.L;
        if (!scattered || !continue_path(depth, sampler, path)) break;
    }
    if (clamp) {
        const Rgb indirect = path.L - direct;
        const float m = max_component(indirect);
        if (m > m_clamp_indirect) return direct + indirect * (m_clamp_indirect / m);
    }
    return path.L;
}

// The steps below are separate functions for reading only: the ones run once per vertex
// are always inlined, so radiance() compiles to one loop whose path state stays in
// registers. scatter(), one copy per BSDF type, is left to the compiler: forcing both
// copies inline makes the loop too large for it to inline their own callees.

// The next vertex along a BSDF-sampled ray (the camera ray was traced in a packet). The
// ray skips the fur strand it leaves.
template <typename Instr>
[[gnu::always_inline]] inline RTCRayHit PathIntegrator::trace(PathState &path,
                                                              RenderStats &stats,
                                                              const Instr &instr) const {
    RTCRayHit rh;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    set_ray(rh.ray, path.o, path.d, inf, std::exchange(path.fur_skip, 0u), path.time);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_rtc, &ctx, &rh);
    instr.ray(path.o, path.d, inf, secondary_ray);
    ++stats.secondary_rays;
    return rh;
}

// Adds what the ray sees of the lights, MIS-weighted against light sampling (Veach 1997
// §9.2) unless the ray came from the camera or a specular bounce. True when the path
// ends: at an area light's own geometry, which emits (front side) and never reflects, or
// when the ray escaped to the environment and distant discs.
[[gnu::always_inline]] inline bool PathIntegrator::add_emission(
    const RTCRayHit &rh, int depth, const CameraRay &cam, PathState &path, FilmSample &fs,
    FilmPointAovs *aovs) const {
    const Lights &lights = m_scene.lights();
    const bool hit_geometry = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    const float t_hit = hit_geometry ? rh.ray.tfar : inf;
    const bool unweighted = depth == 0 || path.prev_specular;
    if (const int li = hit_geometry
                           ? m_scene.geometry().light_of(rh.hit.geomID, rh.hit.instID[0])
                           : -1;
        li >= 0) {
        float pdf_light;
        const Rgb Le = lights.area_radiance(li, path.o, path.d, t_hit, &pdf_light);
        const float w = unweighted ? 1.0f
                                   : power_heuristic(path.prev_pdf,
                                                     lights.select_pdf(li) * pdf_light);
        path.L += path.beta * Le * w;
        if (depth == 0) {
            fs.alpha = 1;
            if (aovs) aovs->depth = t_hit * dot(path.d, cam.forward);
        }
        return true;
    }
    if (!hit_geometry) {
        Lights::InfiniteHit hits[max_infinite_lights];
        const int n =
            lights.eval_infinite(path.d, path.prev_ng, hits, max_infinite_lights);
        for (int k = 0; k < n; ++k) {
            const float w =
                unweighted ? 1.0f : power_heuristic(path.prev_pdf, hits[k].pdf);
            path.L += path.beta * hits[k].L * w;
        }
        return true;
    }
    return false;
}

// The mesh point the ray hit: position, two-sided geometric and shading normals, and
// the ray cone's footprint there (which this adds to the path's).
[[gnu::always_inline]] inline PathIntegrator::SurfaceVertex
PathIntegrator::surface_vertex(const RTCRayHit &rh, PathState &path) const {
    const EmbreeScene &geometry = m_scene.geometry();
    const uint32_t object = geometry.object_of(rh.hit.geomID, rh.hit.instID[0]);
    const ObjectGeometry &og = geometry.objects()[object];
    const MeshData &mesh = *og.mesh;
    const uint32_t prim = rh.hit.primID;
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    const float t_hit = rh.ray.tfar;
    // Normals are built in locals and stored into the vertex once: field-wise writes
    // followed by a whole-Vec3f copy cause store-forwarding stalls.
    Vec3f ng;
    // The hit point from the ray (its float error is far below the origin offset);
    // Embree's Ng for baked meshes, so the vertices are not fetched again.
    if (og.baked) {
        ng = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
    } else {
        // Embree reports Ng of instanced geometry in object space: rebuild and move it.
        const uint32_t *tri = &mesh.triangles[3 * size_t(prim)];
        const Vec3f p0 = mesh.position_at(tri[0], path.time);
        const Vec3f p1 = mesh.position_at(tri[1], path.time);
        const Vec3f p2 = mesh.position_at(tri[2], path.time);
        ng = og.normal_to_world.vector(cross(p1 - p0, p2 - p0));
    }
    const Vec3f wo = -path.d;
    // Two-sided: the geometric normal faces the incoming ray.
    ng = ng * ((dot(ng, wo) < 0 ? -1.0f : 1.0f) / length(ng));
    Vec3f ns_shade = ng;
    if (!mesh.corner_normals.empty()) {
        const size_t c = 3 * size_t(prim);
        Vec3f ns = mesh.corner_normal_at(c, path.time) * b0 +
                   mesh.corner_normal_at(c + 1, path.time) * b1 +
                   mesh.corner_normal_at(c + 2, path.time) * b2;
        if (!og.baked) ns = og.normal_to_world.vector(ns);
        const float len = length(ns);
        if (len > 0) {
            ns = ns / len;
            if (dot(ns, ng) < 0) ns = -ns;
            // A shading normal facing away from the viewer would make the BSDF black.
            if (dot(ns, wo) > 0) ns_shade = ns;
        }
    }
    path.footprint += t_hit * path.spread;
    return {
        object, prim,          b0, b1, b2, t_hit, path.o + path.d * t_hit, ng, ns_shade,
        wo,     path.footprint};
}

// The material plugin fills the BSDF inputs at `sv` (the plugin SDK's PelageHit and
// PelageShade); `albedo` receives its albedo, clamped to [0, 1].
template <typename Instr>
[[gnu::always_inline]] inline PelageShade PathIntegrator::shade(
    const SurfaceVertex &sv, int depth, Rgb *albedo, RenderStats &stats,
    const Instr &instr) const {
    const ObjectGeometry &og = m_scene.geometry().objects()[sv.object];
    const MeshData &mesh = *og.mesh;
    PelageHit ph{};
    ph.object_id = sv.object;
    ph.primitive_id = sv.prim;
    ph.b1 = sv.b1;
    ph.b2 = sv.b2;
    ph.p[0] = sv.p.x;
    ph.p[1] = sv.p.y;
    ph.p[2] = sv.p.z;
    ph.n[0] = sv.ns.x;
    ph.n[1] = sv.ns.y;
    ph.n[2] = sv.ns.z;
    if (!mesh.corner_uvs.empty()) {
        const float *U = &mesh.corner_uvs[6 * size_t(sv.prim)];
        ph.uv[0] = U[0] * sv.b0 + U[2] * sv.b1 + U[4] * sv.b2;
        ph.uv[1] = U[1] * sv.b0 + U[3] * sv.b1 + U[5] * sv.b2;
        ph.has_uv = 1;
    }
    // In the pattern's units: the object's scale undone, then the pose's stretch of
    // this triangle from the rest mesh (a skin's 0.01 armature scale is 100×).
    ph.footprint = sv.footprint * og.to_object_length *
                   (mesh.to_rest_length.empty() ? 1.0f : mesh.to_rest_length[sv.prim]);
    ph.depth = uint32_t(depth);
    PelageShade sh = pelage_default_shade();
    instr.shade(m_scene.materials()[sv.object], ph, sh, stats);
    *albedo = {std::isfinite(sh.albedo[0]) ? std::clamp(sh.albedo[0], 0.0f, 1.0f) : 0.0f,
               std::isfinite(sh.albedo[1]) ? std::clamp(sh.albedo[1], 0.0f, 1.0f) : 0.0f,
               std::isfinite(sh.albedo[2]) ? std::clamp(sh.albedo[2], 0.0f, 1.0f) : 0.0f};
    return sh;
}

// The film's first-hit values for a camera ray that hit a surface.
[[gnu::always_inline]] inline void PathIntegrator::set_first_hit(
    const SurfaceVertex &sv, const PelageShade &sh, const Rgb &albedo,
    const CameraRay &cam, FilmSample &fs, FilmPointAovs *aovs) const {
    fs.alpha = 1;
    fs.albedo = albedo;
    fs.normal = sv.ns;
    if (m_mattes) set_matte_keys(sv, sh, fs);
    if (!aovs) return;
    aovs->depth =
        sv.t_hit * dot(cam.d, cam.forward);  // motion blur: this sample's camera
    aovs->object_id = float(sv.object);
    aovs->primitive_id = float(sv.prim);
    if (sh.aov_written)
        for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS; ++k)
            aovs->shader[k] = std::isfinite(sh.aov[k]) ? sh.aov[k] : 0.0f;
}

// The first hit's Cryptomatte keys, out of line: most renders keep none, and the path's
// hot code stays as short as without them.
[[gnu::noinline]] void PathIntegrator::set_matte_keys(const SurfaceVertex &sv,
                                                      const PelageShade &sh,
                                                      FilmSample &fs) const {
    for (int l = 0; l < m_mattes; ++l) {
        const int slot = m_scene.matte_slot(sv.object, l);
        if (slot == Scene::object_layer) {
            fs.matte[l] = sv.object;
            fs.matte_set |= uint8_t(1u << l);
        } else if (slot >= 0 && (sh.matte_written >> slot & 1u)) {
            fs.matte[l] = uint64_t(sv.object) << 32 | sh.matte[slot];
            fs.matte_set |= uint8_t(1u << l);
        }
    }
}

// Builds the material's BSDF from the plugin's inputs and scatters with it.
template <typename Instr>
[[gnu::always_inline]] inline bool PathIntegrator::scatter_at_surface(
    const SurfaceVertex &sv, const PelageShade &sh, const Rgb &albedo, Sampler &sampler,
    PathState &path, RenderStats &stats, const Instr &instr) const {
    // Braces evaluate in order: the sampler dimensions are consumed as listed.
    const VertexSamples u{sampler.get_2d(), sampler.get_2d(), sampler.get_2d()};
    const Material &mat = m_scene.materials()[sv.object];
    if (mat.bsdf != MaterialDesc::Bsdf::coated)
        return scatter(BsdfLambert(albedo), sv, u, path, stats, instr);
    // The plugin may override the coat's roughness and ior (per cell type, say).
    // The material's precomputed coat terms unless the plugin overrides them.
    const bool own_roughness = sh.roughness >= 0;
    const float roughness = own_roughness ? std::min(sh.roughness, 1.0f) : mat.roughness;
    const bool own_ior = sh.ior >= 1 && sh.ior <= 3;
    const float ior = own_ior ? sh.ior : mat.ior;
    return scatter(
        BsdfCoated(albedo, roughness, ior,
                   own_ior ? BsdfCoated::internal_diffuse_reflectance_table(ior)
                           : mat.coat_F_int,
                   own_ior || own_roughness ? BsdfCoated::specular_albedo(roughness, ior)
                                            : mat.coat_S),
        sv, u, path, stats, instr);
}

// Direct light at the vertex (sample_ld, light_sampling.h), then the continuation: the
// BSDF samples the next direction, which must leave above the geometric surface.
template <typename Bsdf, typename Instr>
bool PathIntegrator::scatter(const Bsdf &bsdf, const SurfaceVertex &sv,
                             const VertexSamples &u, PathState &path, RenderStats &stats,
                             const Instr &instr) const {
    const Frame frame = Frame::from_z(sv.ns);
    const Vec3f wo_local = frame.to_local(sv.wo);
    sample_ld(m_scene.lights(), m_rtc,
              SurfaceLdVertex<Bsdf>{bsdf, frame, wo_local, sv.p, sv.ng, path.time},
              u.pick.u1, u.light.u1, u.light.u2, path.beta, path.L, stats, instr);
    const std::optional<BsdfSample> bs =
        bsdf.sample(wo_local, u.pick.u2, u.bsdf.u1, u.bsdf.u2);
    if (!bs) return false;
    const Vec3f wi = frame.to_world(bs->wi);
    if (dot(wi, sv.ng) <= 0) return false;  // below the geometric surface
    path.beta *= bs->weight;
    path.prev_pdf = bs->pdf;
    path.prev_specular = bs->specular;
    path.prev_ng = sv.ng;
    path.o = offset_ray_origin(sv.p, sv.ng, wi);
    path.d = wi;
    return true;
}

// After a vertex scattered: widens the ray cone for a non-specular bounce (ray_cone.h),
// then decides whether the path goes on. Not when its throughput is black; from rr_depth
// on, Russian roulette (pbrt-v4 §2.2.4) continues with probability min(0.95, √max(β))
// and divides β by it, so the estimate stays unbiased. The square root (Cycles' choice)
// keeps more of the paths whose throughput a first diffuse or hair bounce has halved,
// which still carry much of a pixel's indirect light: ending them costs more noise than
// the time it saves (docs/performance.md, "Noise against time").
[[gnu::always_inline]] inline bool PathIntegrator::continue_path(int depth,
                                                                 Sampler &sampler,
                                                                 PathState &path) const {
    if (is_black(path.beta)) return false;
    if (!path.prev_specular) path.spread += bounce_spread(path.prev_pdf, m_spp);
    if (depth + 1 < m_rr_depth) return true;
    const float p_continue = std::min(0.95f, std::sqrt(max_component(path.beta)));
    if (sampler.get_1d() >= p_continue) return false;
    path.beta = path.beta / p_continue;
    return true;
}

template void PathIntegrator::render_tile(Film &, Sampler &, int, int, int, int, int, int,
                                          RenderStats &, const NoInstrumentation &,
                                          const uint8_t *) const;
template void PathIntegrator::render_tile(Film &, Sampler &, int, int, int, int, int, int,
                                          RenderStats &, const Instrumented &,
                                          const uint8_t *) const;

}  // namespace pelage::renderer
