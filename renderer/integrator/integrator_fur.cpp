#include "renderer/integrator/integrator_fur.h"

#include <cmath>

#include "renderer/core/sampling.h"
#include "renderer/geometry/embree_ray.h"
#include "renderer/integrator/light_sampling.h"
#include "shader/hair/hair_bsdf.h"

namespace pelage::renderer {

namespace {

// The fibre frame: x the tangent, z ⊥ x facing wo, y = z × x.
struct FibreFrame {
    Vec3f x, y, z;
    Vec3f to_local(Vec3f v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
    Vec3f to_world(Vec3f v) const { return x * v.x + y * v.y + z * v.z; }
};

// A strand vertex as sample_ld() sees it: the fibre transmits, so light from either side
// of z counts; shadow rays skip the strand (ray_id).
struct StrandLdVertex {
    const shader::hair::HairBsdf &bsdf;
    const FibreFrame &frame;
    Vec3f wo_local, p, n;
    unsigned ray_id;

    bool accepts(Vec3f) const { return true; }
    Vec3f to_local(Vec3f w) const { return frame.to_local(w); }
    Rgb f(Vec3f wi_local) const { return bsdf.eval(wo_local, wi_local); }
    float pdf(Vec3f wi_local) const { return bsdf.pdf(wo_local, wi_local); }
};

}  // namespace

template <typename Instr>
bool scatter_at_strand(const Scene &scene, const FurLayer &layer, const RTCRayHit &rh,
                       int depth, bool last, Sampler &sampler, FurPathState &st,
                       FilmSample &fs, FilmPointAovs *aovs, const CameraRay &cam,
                       RenderStats &stats, const Instr &instr) {
    const Lights &lights = scene.lights();
    const RTCScene rtc = scene.geometry().scene();
    const Vec3f wo = -st.d;
    const Vec3f p = st.o + st.d * rh.ray.tfar;
    const unsigned prim = rh.hit.primID;
    const uint32_t strand = prim / uint32_t(layer.strands.segments);

    // --- Fibre frame and offset h across the fibre ---
    Vec3f c, x;
    float radius;
    layer.centre(prim, rh.hit.u, &c, &x, &radius);
    // The tube's outward normal: Embree's Ng for round curves; for ribbons, rebuilt from
    // the hit's offset across the centre line as if the ribbon were a tube.
    Vec3f n;
    Vec3f wo_perp = wo - x * dot(wo, x);
    if (length(wo_perp) <= 0) wo_perp = Frame::from_z(x).s;
    wo_perp = normalize(wo_perp);
    if (layer.round) {
        n = Vec3f{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        n = n - x * dot(n, x);
    } else {
        Vec3f e = p - c;
        e = e - x * dot(e, x);
        const float s = std::min(length(e) / std::max(radius, 1e-30f), 1.0f);
        n = e + wo_perp * (radius * std::sqrt(std::max(0.0f, 1 - s * s)));
    }
    n = length(n) > 0 ? normalize(n) : wo_perp;
    const float h = shader::hair::offset_h(x, n, wo);
    // z: the normal turned to face wo (the model only uses φ_i − φ_o, hair_bsdf.h).
    FibreFrame frame;
    frame.x = x;
    frame.z = dot(n, wo) >= 0 ? n : wo_perp;
    frame.y = cross(frame.z, frame.x);

    // --- The strand's BSDF from its melanin ---
    const float eu = layer.strands.melanin[2 * size_t(strand)],
                pheo = layer.strands.melanin[2 * size_t(strand) + 1];
    shader::hair::HairParams hp =
        shader::hair::HairParams::from_melanin(eu, pheo, layer.beta_m, layer.beta_n);
    hp.alpha = layer.alpha;
    const shader::hair::HairBsdf bsdf(hp, h);

    if (depth == 0) {
        fs.alpha = 1;
        fs.albedo = bsdf.albedo();
        fs.normal = frame.z;
        // A strand is in its object's matte, and in the skin's mattes at its root (a
        // spot's hairs are the spot's).
        const uint32_t *root_matte = layer.strands.matte.empty()
                                         ? nullptr
                                         : &layer.strands.matte[4 * size_t(strand)];
        for (size_t l = 0; l < scene.matte_layers().size(); ++l) {
            const int slot = scene.matte_slot(layer.object, int(l));
            if (slot == Scene::object_layer) {
                fs.matte[l] = layer.object;
                fs.matte_set |= uint8_t(1u << l);
            } else if (slot >= 0 && root_matte && (root_matte[3] >> slot & 1u)) {
                fs.matte[l] = uint64_t(layer.object) << 32 | root_matte[slot];
                fs.matte_set |= uint8_t(1u << l);
            }
        }
        if (aovs) {
            aovs->depth = rh.ray.tfar * dot(st.d, cam.forward);
            aovs->object_id = float(layer.object);
            aovs->primitive_id = float(strand);
        }
    }
    if (last) return false;

    const unsigned own_id = layer.strand_offset + strand + 1;
    const Vec3f wo_local = frame.to_local(wo);
    // Three 2D samples, as at a surface (integrator_path.cpp): light and lobe, the point
    // on the light, the BSDF direction; each pair is stratified (sampler.h).
    const auto [u_light, u_lobe] = sampler.get_2d();
    const auto [ul1, ul2] = sampler.get_2d();
    const auto [ub1, ub2] = sampler.get_2d();
    auto origin = [&](Vec3f w) { return offset_ray_origin(p, frame.z, w); };

    // --- Next-event estimation: one light, either side of the fibre ---
    sample_ld(lights, rtc, StrandLdVertex{bsdf, frame, wo_local, p, frame.z, own_id},
              u_light, ul1, ul2, st.beta, st.L, stats, instr);

    // --- Continue the path by sampling the hair BSDF ---
    const auto bs = bsdf.sample(wo_local, u_lobe, ub1, ub2);
    if (!bs) return false;
    const Vec3f wi = frame.to_world({bs->wi.x, bs->wi.y, bs->wi.z});
    st.beta *= bs->weight;
    st.prev_pdf = bs->pdf;
    st.prev_specular = false;
    st.prev_ng = frame.z;
    st.o = origin(wi);
    st.d = wi;
    st.skip_id = own_id;
    return true;
}

template bool scatter_at_strand(const Scene &, const FurLayer &, const RTCRayHit &, int,
                                bool, Sampler &, FurPathState &, FilmSample &,
                                FilmPointAovs *, const CameraRay &, RenderStats &,
                                const NoInstrumentation &);
template bool scatter_at_strand(const Scene &, const FurLayer &, const RTCRayHit &, int,
                                bool, Sampler &, FurPathState &, FilmSample &,
                                FilmPointAovs *, const CameraRay &, RenderStats &,
                                const Instrumented &);

}  // namespace pelage::renderer
