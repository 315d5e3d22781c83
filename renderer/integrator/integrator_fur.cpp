#include "renderer/integrator/integrator_fur.h"

#include <algorithm>
#include <cmath>

#include "renderer/bsdf/hair_bsdf.h"
#include "renderer/core/sampling.h"
#include "renderer/geometry/embree_ray.h"
#include "renderer/integrator/light_sampling.h"

namespace pelage::renderer {

namespace {

// The far field's strata of h (HairBsdf::FarField): 2 at camera hits, 4 at a bounce's.
// On the furry bench cow at 64 spp (`pelage bench noise`, 2 seeds) CPU s × MSE fell
// from 12.7 (near field) to 8.1 with these; 4 and 4 gave 8.7, 8 and 8 9.3, 2 and 2
// 9.3, 8 and 2 11.5: the bounces' strands, lit through the coat, gain the most, and
// each stratum costs a refraction, a Fresnel term and three logistics per evaluation.
constexpr int far_field_camera_nodes = 2;
constexpr int far_field_bounce_nodes = 4;

// A strand vertex as sample_ld() sees it: the fibre transmits, so light from either side
// of z counts; shadow rays skip the strand (ray_id).
struct StrandLdVertex {
    const HairBsdf &bsdf;
    const FibreFrame &frame;
    Vec3f wo_local, p, n;
    unsigned ray_id;
    float time;

    bool accepts(Vec3f) const { return true; }
    Vec3f to_local(Vec3f w) const { return frame.to_local(w); }
    mutable float bsdf_pdf = 0;
    // f and pdf from one evaluation: the far-field model's strata are walked once.
    Rgb f(Vec3f wi_local) const { return bsdf.eval_pdf(wo_local, wi_local, &bsdf_pdf); }
    float pdf(Vec3f) const { return bsdf_pdf; }
};

}  // namespace

// The hit's fibre frame, its offset h across the fibre and the strand's BSDF.
PathIntegrator::StrandVertex PathIntegrator::strand_vertex(const FurLayer &layer,
                                                           const RTCRayHit &rh,
                                                           const PathState &path,
                                                           bool camera_hit) const {
    const Vec3f wo = -path.d;
    Vec3f p = path.o + path.d * rh.ray.tfar;
    const unsigned prim = rh.hit.primID;
    const uint32_t strand = prim / uint32_t(layer.strands.segments);

    Vec3f c, x;
    float radius;
    layer.centre(prim, rh.hit.u, path.time, &c, &x, &radius);
    // The tube's outward normal: Embree's Ng for round curves; for ribbons, rebuilt from
    // the hit's offset across the centre line as if the ribbon were a tube.
    Vec3f n;
    Vec3f wo_perp = wo - x * dot(wo, x);
    if (length(wo_perp) <= 0) wo_perp = Frame::from_z(x).s;
    wo_perp = normalize(wo_perp);
    // A camera ray that keeps a widened strand (fur_geometry.h) hits its widened
    // surface, the fibre lies inside: the hit is rebuilt on the fibre from the ray's
    // closest approach to the centre line, as a ribbon's is, its offset across taken as a
    // fraction of the widened radius (the camera keeps the widened strand with
    // probability own / widened radius), and the path goes on from the fibre.
    if (camera_hit && layer.widened()) {
        const float wide = radius / std::max(layer.opacity(prim, rh.hit.u), 1e-6f);
        const Vec3f w = path.o - c;
        const float b = dot(path.d, x);
        const float den = 1 - b * b;  // path.d is a unit vector
        const float t = den > 1e-12f ? (b * dot(x, w) - dot(path.d, w)) / den : 0.0f;
        const Vec3f q = w + path.d * t;  // the closest point, relative to c
        c = c + x * dot(x, q);
        Vec3f e = q - x * dot(x, q);
        const float s = std::min(length(e) / std::max(wide, 1e-30f), 1.0f);
        e = length(e) > 0 ? e * (s / length(e)) : e;
        n = e + wo_perp * std::sqrt(std::max(0.0f, 1 - s * s));
        p = c + normalize(n) * radius;
    } else if (layer.round) {
        n = Vec3f{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        n = n - x * dot(n, x);
    } else {
        Vec3f e = p - c;
        e = e - x * dot(e, x);
        const float s = std::min(length(e) / std::max(radius, 1e-30f), 1.0f);
        n = e + wo_perp * (radius * std::sqrt(std::max(0.0f, 1 - s * s)));
    }
    n = length(n) > 0 ? normalize(n) : wo_perp;
    const float h = offset_h(x, n, wo);
    // z: the normal turned to face wo (the model only uses φ_i − φ_o, hair_bsdf.h).
    FibreFrame frame;
    frame.x = x;
    frame.z = dot(n, wo) >= 0 ? n : wo_perp;
    frame.y = cross(frame.z, frame.x);

    HairParams hp;
    hp.sigma_a = layer.strands.sigma_a[size_t(strand)];
    hp.beta_m = layer.beta_m_of(strand);
    hp.beta_n = layer.beta_n_of(strand);
    hp.alpha = layer.alpha;
    // Path regularisation (Kaplanyan & Dachsbacher 2013, "Path Space Regularization for
    // Holistic and Robust Light Transport"; Cycles' Filter Glossy does the same for
    // glossy surfaces): past the camera hit, a fibre's narrow lobes only pick which
    // strand or patch of sky a path goes on to, and a coat of thousands of strands
    // averages that choice away, so widening them changes the image little and cuts the
    // paths whose throughput a second strand's R highlight multiplies. The lobes stay
    // normalised (M_p, N_p integrate to 1), so energy is kept. On the furry bench cow at
    // 64 spp, β ≥ 0.4 takes the variance down 1.28× at a mean within 1 % per channel
    // (docs/validation.md, "Fur at a distance").
    if (!camera_hit && m_fur_bounce_roughness > 0) {
        hp.beta_m = std::max(hp.beta_m, m_fur_bounce_roughness);
        hp.beta_n = std::max(hp.beta_n, m_fur_bounce_roughness);
    }
    // The far-field model (hair_bsdf.h) where a ray's h is uniform over the fibre's
    // width: at every strand a bounce or shadow-casting path reaches, and where a camera
    // ray meets a strand narrower than the pixel at that distance (its samples spread
    // over the whole width). Its strata's offset ξ is the hit's own place in its stratum,
    // uniform wherever h is: the hit's h is one of the points and no sampler dimension is
    // drawn. Strands wider than a pixel keep the near-field model, its highlight across
    // the fibre resolved.
    if (m_fur_far_field && (!camera_hit || 2 * radius < rh.ray.tfar * m_pixel_angle)) {
        const int K = camera_hit ? far_field_camera_nodes : far_field_bounce_nodes;
        const float scaled = 0.5f * (h + 1) * float(K);
        const float xi = std::clamp(scaled - std::floor(scaled), 0.0f, 0x1.fffffep-1f);
        return {layer,
                strand,
                p,
                wo,
                rh.ray.tfar,
                frame,
                HairBsdf(hp, HairBsdf::FarField{K, xi})};
    }
    return {layer, strand, p, wo, rh.ray.tfar, frame, HairBsdf(hp, h)};
}

// The film's first-hit values for a camera ray that hit a strand. A strand is in its
// object's matte, and in the skin's mattes at its root (a spot's hairs are the spot's).
void PathIntegrator::set_first_hit(const StrandVertex &v, const CameraRay &cam,
                                   FilmSample &fs, FilmPointAovs *aovs) const {
    const FurLayer &layer = v.layer;
    fs.alpha = 1;
    fs.albedo = v.bsdf.albedo();
    fs.normal = v.frame.z;
    const uint32_t *root_matte = layer.strands.matte.empty()
                                     ? nullptr
                                     : &layer.strands.matte[4 * size_t(v.strand)];
    for (size_t l = 0; l < m_scene.matte_layers().size(); ++l) {
        const int slot = m_scene.matte_slot(layer.object, int(l));
        if (slot == Scene::object_layer) {
            fs.matte[l] = layer.object;
            fs.matte_set |= uint8_t(1u << l);
        } else if (slot >= 0 && root_matte && (root_matte[3] >> slot & 1u)) {
            fs.matte[l] = uint64_t(layer.object) << 32 | root_matte[slot];
            fs.matte_set |= uint8_t(1u << l);
        }
    }
    if (aovs) {
        aovs->depth = v.t_hit * dot(-v.wo, cam.forward);
        aovs->object_id = float(layer.object);
        aovs->primitive_id = float(v.strand);
    }
}

// Direct light from either side of the fibre, then the continuation the hair BSDF
// samples. The next ray skips this strand.
template <typename Instr>
bool PathIntegrator::scatter_at_strand(const StrandVertex &v, Sampler &sampler,
                                       PathState &path, RenderStats &stats,
                                       const Instr &instr) const {
    const unsigned own_id = v.layer.strand_offset + v.strand + 1;
    const Vec3f wo_local = v.frame.to_local(v.wo);
    // Three 2D samples, as at a surface (integrator_path.cpp): light and lobe, the point
    // on the light, the BSDF direction; each pair is stratified (sampler.h).
    const auto [u_light, u_lobe] = sampler.get_2d();
    const auto [ul1, ul2] = sampler.get_2d();
    const auto [ub1, ub2] = sampler.get_2d();

    sample_ld(
        m_scene.lights(), m_rtc,
        StrandLdVertex{v.bsdf, v.frame, wo_local, v.p, v.frame.z, own_id, path.time},
        u_light, ul1, ul2, path.beta, path.L, stats, instr);

    const std::optional<BsdfSample> bs = v.bsdf.sample(wo_local, u_lobe, ub1, ub2);
    if (!bs) return false;
    const Vec3f wi = v.frame.to_world(bs->wi);
    path.beta *= bs->weight;
    path.prev_pdf = bs->pdf;
    path.prev_specular = false;
    path.prev_ng = v.frame.z;
    path.o = offset_ray_origin(v.p, v.frame.z, wi);
    path.d = wi;
    path.fur_skip = own_id;
    return true;
}

template bool PathIntegrator::scatter_at_strand(const StrandVertex &, Sampler &,
                                                PathState &, RenderStats &,
                                                const NoInstrumentation &) const;
template bool PathIntegrator::scatter_at_strand(const StrandVertex &, Sampler &,
                                                PathState &, RenderStats &,
                                                const Instrumented &) const;

}  // namespace pelage::renderer
