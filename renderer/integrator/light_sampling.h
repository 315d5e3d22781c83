// Next-event estimation at a path vertex (pbrt-v4 §13.4, SampleLd), shared by surface
// and fur-strand vertices: one light, chosen by the scene's light selection, is sampled
// and, when unoccluded, adds β·f·Li·|cos θ|·w / p to L, with the power heuristic weight
// w against BSDF sampling (Veach 1997 §9.2).
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
//   accepts(wi)  whether light from world direction wi can scatter here;
//   to_local(wi) the direction in the shading frame (z: the normal |cos θ| uses);
//   f(wi_local)  the BSDF value; then, only for a visible light that is not a delta,
//   pdf(wi_local) the BSDF's sampling density of wi_local.
// β multiplies first (β·f·Li·…): the product's order is part of the image.
template <typename Vertex, typename Instr>
void sample_ld(const Lights &lights, RTCScene rtc, const Vertex &vertex, float u_light,
               float u1, float u2, Rgb beta, Rgb &L, RenderStats &stats,
               const Instr &instr) {
    LightSample ls;
    float select_pdf = 0;
    const int li = lights.count() > 0 ? lights.select(u_light, &select_pdf) : -1;
    if (li < 0 || !lights.sample(li, vertex.p, vertex.n, u1, u2, &ls) ||
        !vertex.accepts(ls.wi))
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
    set_ray(sr, so, ls.wi, tfar, vertex.ray_id);
    rtcOccluded1(rtc, &sctx, &sr);
    instr.ray(so, ls.wi, tfar, shadow_ray);
    ++stats.shadow_rays;
    if (!(sr.tfar >= 0)) return;  // Embree sets tfar = -inf when occluded
    const float light_pdf = select_pdf * ls.pdf;
    const float w = ls.delta ? 1.0f : power_heuristic(light_pdf, vertex.pdf(wi_local));
    L += beta * f * ls.Li * (std::abs(wi_local.z) * w / light_pdf);
}

}  // namespace pelage::renderer
