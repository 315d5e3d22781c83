// A diffuse base under a rough dielectric coat: GGX microfacet reflection from the coat
// (Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", EGSR,
// eqs. 20 (Fresnel-weighted Cook-Torrance), 33 (D) and 34 (G1)) plus the base, seen
// through the coat and attenuated by the transmittance (1 − F) on the way in and out:
//   f = F(wo·h) D(h) G2(wo, wi) / (4 cos θ_o cos θ_i) + (1 − F(cos θ_i))(1 − F(cos θ_o))
//   ρ/π.
// This ignores inter-reflection between coat and base (energy is lost, never gained).
// The specular lobe is sampled from the distribution of visible normals (Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)).
#pragma once

#include "renderer/bsdf.h"

namespace pelage::renderer {

class BsdfCoated {
  public:
    // roughness: perceptual, α = roughness²; clamped so the lobe stays samplable.
    BsdfCoated(Rgb rho, float roughness, float ior);

    Rgb eval(Vec3f wo, Vec3f wi) const;
    float pdf(Vec3f wo, Vec3f wi) const;
    std::optional<BsdfSample> sample(Vec3f wo, float u_lobe, float u1, float u2) const;
    Rgb albedo() const { return m_rho; }

    // Unpolarized Fresnel reflectance of a dielectric with relative index eta.
    static float fresnel_dielectric(float cos_i, float eta);
    float distribution(Vec3f h) const;  // D(h), GGX
    float smith_g1(Vec3f w) const;      // G1(w), GGX

  private:
    // Terms that depend on wo only, computed once per wo: a BSDF is built per hit and
    // eval/pdf/sample are called several times with the same wo. Not thread-safe (a BSDF
    // is a per-hit local value).
    struct WoTerms {
        float cos_o = -2, F_o = 0, G1_o = 0, p_spec = 0;
    };
    const WoTerms &wo_terms(Vec3f wo) const;
    float specular_probability(Vec3f wo) const { return wo_terms(wo).p_spec; }
    mutable WoTerms m_wo;

    Rgb m_rho;
    float m_alpha, m_eta;
};

static_assert(Bsdf<BsdfCoated>);

}  // namespace pelage::renderer
