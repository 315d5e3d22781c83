#include "renderer/integrator/integrator_path.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "renderer/bsdf/bsdf_coated.h"
#include "renderer/bsdf/bsdf_lambert.h"
#include "renderer/core/ray_cone.h"
#include "renderer/core/sampling.h"
#include "renderer/geometry/embree_ray.h"
#include "renderer/integrator/integrator_fur.h"

namespace pelage::renderer {

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr int max_infinite_lights = 8;
constexpr double max_plugin_call_seconds = 100e-6;  // see the plugin timing below
constexpr float shadow_ray_shortening =
    1e-4f;  // keep shadow rays off the light's surface

struct Vertex {
    Vec3f p, ng, ns, wo;
};

void record(std::vector<RecordedRay> *log, Vec3f o, Vec3f d, float tfar, uint32_t kind) {
    if (log) log->push_back({{o.x, o.y, o.z}, tfar, {d.x, d.y, d.z}, kind});
}

// The cost of the two clock reads around a timed plugin call (the fastest of many
// back-to-back pairs), subtracted from each timing: in a VM a clock read can cost more
// than a simple plugin.
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

}  // namespace

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

PathIntegrator::PathIntegrator(const Scene &scene, const Camera &camera,
                               const PixelFilter &filter, int /*width*/, int height)
    : m_scene(scene),
      m_camera(camera),
      m_filter(filter),
      m_rtc(scene.geometry().scene()),
      m_packets(scene.geometry().device(), scene.geometry().scene()),
      m_max_depth(scene.desc().integrator.max_depth),
      m_rr_depth(scene.desc().integrator.rr_depth),
      m_spp(scene.desc().film.spp) {
    m_timer_overhead = timer_overhead_seconds();
    m_pixel_spread = 2 * std::tan(0.5f * scene.desc().camera.fov_deg * pi / 180) /
                     float(height) * camera_spread_scale(m_spp);
}

void PathIntegrator::render_tile(Film &film, Sampler &sampler, int x0, int y0, int x1,
                                 int y1, int s0, int s1, RenderStats &stats,
                                 std::vector<RecordedRay> *log) const {
    constexpr int K = PacketIntersector::max_rays;
    Sampler lane[K];
    CameraRay cam[K];
    Vec3f org[K], dir[K];
    RTCRayHit first[K];
    // Row by row, sample by sample, K neighbouring pixels at a time: their camera rays
    // form one coherent packet. Each pixel still receives its samples in sample order.
    // The rows run back and forth (boustrophedon), so consecutive camera hits stay
    // neighbours where one row ends and the next begins: shaders that reuse the previous
    // hit's work (the clonal mosaic's CoherentLookup) reuse it there too. Pixels are
    // independent (own sampler, own film pixel), so the order changes no result.
    const int packets = (x1 - x0 + K - 1) / K;
    int sweep = 0;
    for (int y = y0; y < y1; ++y)
        for (int s = s0; s < s1; ++s, ++sweep)
            for (int p = 0; p < packets; ++p) {
                const bool backwards = sweep & 1;
                const int xs = x0 + K * (backwards ? packets - 1 - p : p);
                const int n = std::min(K, x1 - xs);
                // --- Camera rays, offsets drawn from the filter (every sample has
                // weight 1) ---
                for (int i = 0; i < n; ++i) {
                    Sampler &sp = lane[i];
                    sp = sampler;
                    sp.start_pixel_sample(uint32_t(xs + i), uint32_t(y), uint32_t(s));
                    const auto [fu, fv] = sp.get_2d();
                    const float dx = m_filter.sample_1d(fu), dy = m_filter.sample_1d(fv);
                    const auto [lu, lv] = sp.get_2d();
                    const float px = float(xs + i) + 0.5f + dx, py = float(y) + 0.5f + dy;
                    cam[i] = m_motion ? m_motion(sp.get_1d()).generate(px, py, lu, lv)
                                      : m_camera.generate(px, py, lu, lv);
                    org[i] = cam[i].o;
                    dir[i] = cam[i].d;
                }
                m_packets.intersect(org, dir, n, first);
                stats.camera_rays += uint64_t(n);
                for (int i = 0; i < n; ++i) record(log, org[i], dir[i], inf, 0);
                // --- The paths, one pixel at a time ---
                for (int j = 0; j < n; ++j) {
                    const int i = backwards ? n - 1 - j : j, x = xs + i;
                    FilmSample fs;
                    FilmPointAovs aovs;
                    fs.L = radiance(cam[i], first[i], lane[i], fs,
                                    s == 0 ? &aovs : nullptr, stats, log);
                    ++stats.samples;
                    if (s == 0) film.set_point_aovs(x, y, aovs);
                    // No NaN or Inf reaches the film: drop the sample and count it.
                    if (!is_finite(fs.L) || !is_finite(fs.albedo) ||
                        !is_finite(fs.normal)) {
                        ++stats.nonfinite_samples;
                        continue;
                    }
                    film.add(x, y, 1.0f, fs);
                }
            }
}

Rgb PathIntegrator::radiance(const CameraRay &cam, const RTCRayHit &first,
                             Sampler &sampler, FilmSample &fs, FilmPointAovs *aovs,
                             RenderStats &stats, std::vector<RecordedRay> *log) const {
    const Lights &lights = m_scene.lights();
    const EmbreeScene &geometry = m_scene.geometry();
    const int num_lights = lights.count();

    Rgb L{}, beta{1, 1, 1};
    Vec3f o = cam.o, d = cam.d;
    float prev_pdf = 0;  // solid-angle density of the BSDF sample that made d
    bool prev_specular = false;
    Vec3f prev_ng{0, 0, 1};         // geometric normal at the vertex d left
    float footprint = 0;            // ray cone width at the ray origin (ray_cone.h)
    float spread = m_pixel_spread;  // ... and its full angle, radians
    unsigned fur_skip = 0;          // the strand the ray leaves, + 1 (fur_geometry.h)

    for (int depth = 0;; ++depth) {
        // --- Intersect the scene (the camera ray was traced in a packet) ---
        RTCRayHit rh;
        if (depth == 0) {
            rh = first;
        } else {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
            set_ray(rh.ray, o, d, inf);
            rh.ray.id = std::exchange(fur_skip, 0u);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(m_rtc, &ctx, &rh);
        }
        if (depth > 0) {  // camera rays were counted and recorded with their packet
            record(log, o, d, inf, 1);
            ++stats.secondary_rays;
        }
        const bool hit_geometry = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        const float t_hit = hit_geometry ? rh.ray.tfar : inf;
        const bool unweighted = depth == 0 || prev_specular;

        // --- An area light's own geometry: emits (front side), never reflects ---
        if (const int li =
                hit_geometry ? geometry.light_of(rh.hit.geomID, rh.hit.instID[0]) : -1;
            li >= 0) {
            float pdf_light;
            const Rgb Le = lights.area_radiance(li, o, d, t_hit, &pdf_light);
            const float w =
                unweighted ? 1.0f
                           : power_heuristic(prev_pdf, lights.select_pdf(li) * pdf_light);
            L += beta * Le * w;
            if (depth == 0) {
                fs.alpha = 1;
                if (aovs) aovs->depth = t_hit * dot(d, cam.forward);
            }
            break;
        }
        // --- Escaped: the environment and distant discs ---
        if (!hit_geometry) {
            Lights::InfiniteHit hits[max_infinite_lights];
            const int n = lights.eval_infinite(d, prev_ng, hits, max_infinite_lights);
            for (int k = 0; k < n; ++k) {
                const float w =
                    unweighted ? 1.0f : power_heuristic(prev_pdf, hits[k].pdf);
                L += beta * hits[k].L * w;
            }
            break;
        }

        // --- Fur: a strand scatters with the hair BSDF
        // (renderer/integrator/integrator_fur.h) ---
        if (const FurLayer *layer =
                m_scene.fur() ? m_scene.fur()->layer_of(rh.hit.geomID) : nullptr) {
            FurPathState st{L, beta, o, d, prev_pdf, prev_specular, prev_ng, fur_skip};
            if (!scatter_at_strand(m_scene, *layer, rh, depth, depth >= m_max_depth,
                                   sampler, st, fs, aovs, cam, stats, log) ||
                is_black(beta))
                break;
            if (!prev_specular) spread += bounce_spread(prev_pdf, m_spp);
            if (depth + 1 >= m_rr_depth) {
                const float p_continue = std::min(0.95f, max_component(beta));
                if (sampler.get_1d() >= p_continue) break;
                beta = beta / p_continue;
            }
            continue;
        }

        // --- Surface geometry at the hit ---
        const uint32_t object = geometry.object_of(rh.hit.geomID, rh.hit.instID[0]);
        const ObjectGeometry &og = geometry.objects()[object];
        const MeshData &mesh = *og.mesh;
        const uint32_t prim = rh.hit.primID;
        const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
        // Normals are built in locals and stored into the vertex once: field-wise writes
        // followed by a whole-Vec3f copy cause store-forwarding stalls.
        Vec3f ng;
        // The hit point from the ray (its float error is far below the origin offset);
        // Embree's Ng for baked meshes, so the vertices are not fetched again.
        if (og.baked) {
            ng = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        } else {
            // Embree reports Ng of instanced geometry in object space: rebuild and move
            // it.
            const uint32_t *tri = &mesh.triangles[3 * size_t(prim)];
            const float *P = mesh.positions.data();
            const Vec3f p0{P[3 * tri[0]], P[3 * tri[0] + 1], P[3 * tri[0] + 2]};
            const Vec3f p1{P[3 * tri[1]], P[3 * tri[1] + 1], P[3 * tri[1] + 2]};
            const Vec3f p2{P[3 * tri[2]], P[3 * tri[2] + 1], P[3 * tri[2] + 2]};
            ng = og.normal_to_world.vector(cross(p1 - p0, p2 - p0));
        }
        const Vec3f wo = -d;
        // Two-sided: the geometric normal faces the incoming ray.
        ng = ng * ((dot(ng, wo) < 0 ? -1.0f : 1.0f) / length(ng));
        Vec3f ns_shade = ng;
        if (!mesh.corner_normals.empty()) {
            const float *N = &mesh.corner_normals[9 * size_t(prim)];
            Vec3f ns = Vec3f{N[0], N[1], N[2]} * b0 + Vec3f{N[3], N[4], N[5]} * b1 +
                       Vec3f{N[6], N[7], N[8]} * b2;
            if (!og.baked) ns = og.normal_to_world.vector(ns);
            const float len = length(ns);
            if (len > 0) {
                ns = ns / len;
                if (dot(ns, ng) < 0) ns = -ns;
                // A shading normal facing away from the viewer would make the BSDF black.
                if (dot(ns, wo) > 0) ns_shade = ns;
            }
        }
        const Vertex v{o + d * t_hit, ng, ns_shade, wo};
        footprint += t_hit * spread;

        // --- Shade: the material plugin fills the BSDF inputs ---
        const Material &mat = m_scene.materials()[object];
        PelageHit ph{};
        ph.object_id = object;
        ph.primitive_id = prim;
        ph.b1 = b1;
        ph.b2 = b2;
        ph.p[0] = v.p.x;
        ph.p[1] = v.p.y;
        ph.p[2] = v.p.z;
        ph.n[0] = v.ns.x;
        ph.n[1] = v.ns.y;
        ph.n[2] = v.ns.z;
        if (!mesh.corner_uvs.empty()) {
            const float *U = &mesh.corner_uvs[6 * size_t(prim)];
            ph.uv[0] = U[0] * b0 + U[2] * b1 + U[4] * b2;
            ph.uv[1] = U[1] * b0 + U[3] * b1 + U[5] * b2;
            ph.has_uv = 1;
        }
        ph.footprint = footprint * og.to_object_length;
        ph.depth = uint32_t(depth);
        PelageShade sh{};
        sh.albedo[0] = sh.albedo[1] = sh.albedo[2] = 0.5f;
        sh.roughness = -1;
        if (stats.plugin_calls++ % m_plugin_timing_stride == 0) {
            const auto t0 = std::chrono::steady_clock::now();
            mat.plugin->shade(mat.instance, &ph, &sh);
            const double dt =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                    .count();
            // A call that took longer than this was preempted (the thread lost its core);
            // one such sample, extrapolated 16×, would dominate the estimate on a
            // shared machine. It is left out of the mean, not counted as shading.
            if (dt < max_plugin_call_seconds) {
                stats.plugin_timed_seconds += std::max(0.0, dt - m_timer_overhead);
                ++stats.plugin_timed_calls;
            }
        } else {
            mat.plugin->shade(mat.instance, &ph, &sh);
        }
        Rgb albedo{sh.albedo[0], sh.albedo[1], sh.albedo[2]};
        albedo = {std::isfinite(albedo.x) ? std::clamp(albedo.x, 0.0f, 1.0f) : 0.0f,
                  std::isfinite(albedo.y) ? std::clamp(albedo.y, 0.0f, 1.0f) : 0.0f,
                  std::isfinite(albedo.z) ? std::clamp(albedo.z, 0.0f, 1.0f) : 0.0f};

        if (depth == 0) {
            fs.alpha = 1;
            fs.albedo = albedo;
            fs.normal = v.ns;
            if (aovs) {
                aovs->depth =
                    t_hit * dot(d, cam.forward);  // motion blur: this sample's camera
                aovs->object_id = float(object);
                aovs->primitive_id = float(prim);
                if (sh.aov_written)
                    for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS; ++k)
                        aovs->shader[k] = std::isfinite(sh.aov[k]) ? sh.aov[k] : 0.0f;
            }
        }
        if (depth >= m_max_depth) break;

        // --- Direct lighting and BSDF sampling, for the material's BSDF ---
        const Frame frame = Frame::from_z(v.ns);
        const Vec3f wo_local = frame.to_local(v.wo);
        // Named floats, not structured bindings: the lambda below captures them, which
        // C++17 (and clang before 16) does not allow for bindings.
        const Sampler::Pair u_pick = sampler.get_2d(), u_light_pos = sampler.get_2d(),
                            u_bsdf = sampler.get_2d();
        const float u_light = u_pick.u1, u_lobe = u_pick.u2;
        const float ul1 = u_light_pos.u1, ul2 = u_light_pos.u2;
        const float ub1 = u_bsdf.u1, ub2 = u_bsdf.u2;
        auto scatter = [&](const auto &bsdf) -> bool {
            // --- Next-event estimation: one light, chosen by its power ---
            LightSample ls;
            float select_pdf = 0;
            const int li = num_lights > 0 ? lights.select(u_light, &select_pdf) : -1;
            if (li >= 0 && lights.sample(li, v.p, v.ng, ul1, ul2, &ls) &&
                dot(ls.wi, v.ng) > 0) {
                const Vec3f wi_local = frame.to_local(ls.wi);
                float bsdf_pdf;
                const Rgb f = eval_with_pdf(bsdf, wo_local, wi_local, &bsdf_pdf);
                if (!is_black(f)) {
                    const Vec3f so = offset_ray_origin(v.p, v.ng, ls.wi);
                    const float tfar = std::isinf(ls.distance)
                                           ? inf
                                           : ls.distance * (1 - shadow_ray_shortening);
                    RTCIntersectContext sctx;
                    rtcInitIntersectContext(&sctx);
                    sctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
                    RTCRay sr;
                    set_ray(sr, so, ls.wi, tfar);
                    rtcOccluded1(m_rtc, &sctx, &sr);
                    record(log, so, ls.wi, tfar, 2);
                    ++stats.shadow_rays;
                    if (sr.tfar >= 0) {  // Embree sets tfar = -inf when occluded
                        const float light_pdf = select_pdf * ls.pdf;
                        const float w =
                            ls.delta ? 1.0f : power_heuristic(light_pdf, bsdf_pdf);
                        L += beta * f * ls.Li * (std::abs(wi_local.z) * w / light_pdf);
                    }
                }
            }
            // --- Continue the path by sampling the BSDF ---
            const std::optional<BsdfSample> bs = bsdf.sample(wo_local, u_lobe, ub1, ub2);
            if (!bs) return false;
            const Vec3f wi = frame.to_world(bs->wi);
            if (dot(wi, v.ng) <= 0) return false;  // below the geometric surface
            beta *= bs->weight;
            prev_pdf = bs->pdf;
            prev_specular = bs->specular;
            prev_ng = v.ng;
            o = offset_ray_origin(v.p, v.ng, wi);
            d = wi;
            return true;
        };
        bool go_on;
        if (mat.bsdf == MaterialDesc::Bsdf::coated) {
            // The plugin may override the coat's roughness and ior (per cell type, say).
            const float roughness =
                sh.roughness >= 0 ? std::min(sh.roughness, 1.0f) : mat.roughness;
            const bool own_ior = sh.ior >= 1 && sh.ior <= 3;
            go_on = scatter(BsdfCoated(
                albedo, roughness, own_ior ? sh.ior : mat.ior,
                own_ior ? BsdfCoated::internal_diffuse_reflectance_table(sh.ior)
                        : mat.coat_F_int));
        } else {
            go_on = scatter(BsdfLambert(albedo));
        }
        if (!go_on || is_black(beta)) break;
        if (!prev_specular) spread += bounce_spread(prev_pdf, m_spp);

        // --- Russian roulette ---
        if (depth + 1 >= m_rr_depth) {
            const float p_continue = std::min(0.95f, max_component(beta));
            if (sampler.get_1d() >= p_continue) break;
            beta = beta / p_continue;
        }
    }
    return L;
}

}  // namespace pelage::renderer
