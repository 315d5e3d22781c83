// Next-event estimation at a path vertex (pbrt-v4 §13.4, SampleLd), shared by surface
// and fur-strand vertices: every light, or one chosen by the scene's light selection, is
// sampled and, when unoccluded, adds β·f·Li·|cos θ|·w / p to L, with the power heuristic
// weight w against BSDF sampling (Veach 1997 §9.2).
#pragma once

#include <cmath>
#include <limits>

#include "renderer/core/sampling.h"
#include "renderer/geometry/embree_ray.h"
#include "renderer/integrator/instrumentation.h"
#include "renderer/lights/lights.h"

namespace pelage::renderer {

// Keeps shadow rays off the light's surface: they stop this fraction short of it.
constexpr float shadow_ray_shortening = 1e-4f;

// `vertex` is where light arrives, in its shading frame:
//   p, n         the point, and the normal lights are sampled about and shadow rays
//                leave along (offset_ray_origin);
//   ray_id       the shadow ray's id (fur_geometry.h: the strand it must skip);
//   time         the path's time in the shutter (the shadow ray's);
//   accepts(wi)  whether light from world direction wi can scatter here;
//   to_local(wi) the direction in the shading frame (z: the normal |cos θ| uses);
//   f(wi_local)  the BSDF value; then, only for a visible light that is not a delta,
//   pdf(wi_local) the BSDF's sampling density of wi_local.
// β multiplies first (β·f·Li·…): the product's order is part of the image.
// One light's contribution: sampled with (u1, u2) and, when unoccluded, added to L
// with its probability of being chosen, select_pdf.
template <typename Vertex, typename Instr>
void sample_one_light(const Lights &lights, RTCScene rtc, const Vertex &vertex, int li,
                      float select_pdf, float u1, float u2, Rgb beta, Rgb &L,
                      RenderStats &stats, const Instr &instr) {
    LightSample ls;
    if (!lights.sample(li, vertex.p, vertex.n, u1, u2, &ls) || !vertex.accepts(ls.wi))
        return;
    const Vec3f wi_local = vertex.to_local(ls.wi);
    const Rgb f = vertex.f(wi_local);
    if (is_black(f)) return;
    const Vec3f so = offset_ray_origin(vertex.p, vertex.n, ls.wi);
    const float tfar = std::isinf(ls.distance)
                           ? std::numeric_limits<float>::infinity()
                           : ls.distance * (1 - shadow_ray_shortening);
    RTCIntersectContext sctx;
    rtcInitIntersectContext(&sctx);
    sctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    RTCRay sr;
    set_ray(sr, so, ls.wi, tfar, vertex.ray_id, vertex.time);
    rtcOccluded1(rtc, &sctx, &sr);
    instr.ray(so, ls.wi, tfar, shadow_ray);
    ++stats.shadow_rays;
    if (!(sr.tfar >= 0)) return;  // Embree sets tfar = -inf when occluded
    const float light_pdf = select_pdf * ls.pdf;
    const float w = ls.delta ? 1.0f : power_heuristic(light_pdf, vertex.pdf(wi_local));
    L += beta * f * ls.Li * (std::abs(wi_local.z) * w / light_pdf);
}

// Every light (Lights::sample_all) or the one the selection picks with u_light. Light k
// of all samples (u1, u2) shifted by k times the R2 sequence's step (1/g, 1/g²), g the
// plastic number: a shifted (Cranley-Patterson rotated) stratified set stays
// stratified, so each light keeps the sampler's stratification across a pixel's samples
// without drawing more dimensions.
template <typename Vertex, typename Instr>
void sample_ld(const Lights &lights, RTCScene rtc, const Vertex &vertex, float u_light,
               float u1, float u2, Rgb beta, Rgb &L, RenderStats &stats,
               const Instr &instr) {
    if (lights.nee_count() == 0) return;
    if (lights.sample_all()) {
        for (int k = 0; k < lights.count(); ++k) {
            if (lights.select_pdf(k) == 0) continue;  // not a next-event light
            float v1 = u1 + float(k) * 0.7548777f, v2 = u2 + float(k) * 0.5698403f;
            v1 -= float(int(v1));
            v2 -= float(int(v2));
            sample_one_light(lights, rtc, vertex, k, 1.0f, v1, v2, beta, L, stats, instr);
        }
        return;
    }
    float select_pdf = 0;
    const int li = lights.select(u_light, &select_pdf);
    sample_one_light(lights, rtc, vertex, li, select_pdf, u1, u2, beta, L, stats, instr);
}

}  // namespace pelage::renderer
