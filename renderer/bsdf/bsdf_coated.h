// A diffuse base under a rough dielectric coat: GGX microfacet reflection from the coat
// (Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", EGSR,
// eqs. 20 (Fresnel-weighted Cook-Torrance), 33 (D) and 34 (G1)) plus the base, seen
// through the coat:
//   f = F(wo·h) D(h) G2(wo, wi) / (4 cos θ_o cos θ_i)
//     + (1 − F(cos θ_i)) (1 − F(cos θ_o)) ρ / (π η² (1 − ρ F̄_int)).
// The second term is the smooth-coat layering of a Lambertian base (as in Mitsuba 3's
// roughplastic plugin, src/bsdfs/roughplastic.cpp, after Weidlich & Wilkie 2007,
// "Arbitrarily Layered Micro-Facet Surfaces", GRAPHITE): light refracted in with (1 −
// F_i) reflects diffusely under the coat; a fraction F̄_int of it (the hemispherical mean
// of the internal Fresnel reflectance) is sent back to the base each time, which the
// geometric series 1 / (1 − ρ F̄_int) sums, and leaving the denser coat divides radiance
// by η². With ρ = 1 the base term alone reflects exactly 1 − F(cos θ_i).
// Model limitation (measured by BsdfCoated.WhiteFurnace* in
// tests/renderer/bsdf/bsdf_test.cpp): the coat is single-scattering GGX and its
// transmittance is the smooth 1 − F(cos θ), while a rough coat reflects less than F(cos
// θ) at grazing angles. A white base keeps ≥ 97 % of the energy at normal incidence; at
// cos θ_o = 0.1 it keeps 99 % (roughness 0.1), 65 % (0.4), 47 % (1.0). Coupling the base
// to the coat's directional albedo (Kelemen & Szirmay-Kalos 2001) would close the gap; it
// needs a per-ior table. The specular lobe is sampled from the distribution of visible
// normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)).
//
// The colour a material gives is the surface's reflectance, as a base colour is in
// Principled/OpenPBR shading: the base ρ is chosen per channel so that the whole BSDF's
// bihemispherical albedo (what a flat-coloured object shows in a white furnace, averaged
// over its projected area) equals the colour,
//   S̄ + (1 − F̄_ext) g = colour,  g = ρ (1 − F̄_int) / (1 − ρ F̄_int),
// where S̄ is the coat's own bihemispherical albedo (specular_albedo: a table over
// roughness and ior) and (1 − F̄_ext) g the base's, seen through the coat (the base term
// above integrated over both hemispheres; g = 1 for ρ = 1). Colours below S̄ (about 0.04
// to 0.1) cannot be reached, a glossy black still reflects its coat, and g is at most 1.
#pragma once

#include <algorithm>

#include "renderer/bsdf/bsdf.h"

namespace pelage::renderer {

class BsdfCoated {
  public:
    // colour: the reflectance (bihemispherical albedo) the surface shows, in [0, 1].
    // roughness: perceptual, α = roughness²; clamped so the lobe stays samplable.
    // F_int: internal_diffuse_reflectance(ior), precomputed per material (the
    // three-argument form computes it and S, for tests and one-off use).
    // S: specular_albedo(roughness, ior), likewise precomputed per material.
    BsdfCoated(Rgb colour, float roughness, float ior, float F_int, float S);
    BsdfCoated(Rgb colour, float roughness, float ior)
        : BsdfCoated(colour, roughness, ior, internal_diffuse_reflectance(ior),
                     specular_albedo(roughness, ior)) {}

    Rgb eval(Vec3f wo, Vec3f wi) const;
    float pdf(Vec3f wo, Vec3f wi) const;
    // eval() and pdf() in one: they share h, D(h) and the Fresnel terms.
    Rgb eval_pdf(Vec3f wo, Vec3f wi, float *pdf) const;
    std::optional<BsdfSample> sample(Vec3f wo, float u_lobe, float u1, float u2) const;
    Rgb albedo() const { return m_colour; }

    // Unpolarized Fresnel reflectance of a dielectric with relative index eta.
    static float fresnel_dielectric(float cos_i, float eta);
    // F̄_int: the cosine-weighted hemispherical mean of Fresnel reflectance for light
    // inside a medium of index eta, 1 − (1 − F̄_ext) / η² with F̄_ext = 2 ∫ F(μ) μ dμ
    // (by flux balance across the interface). Numerical quadrature: not for hot loops.
    static float internal_diffuse_reflectance(float eta);
    // The same from a table over eta in [1, 3] (linear interpolation, within 2e-5 of the
    // quadrature), for an ior that changes per hit (a plugin's override).
    static float internal_diffuse_reflectance_table(float eta);
    // S̄: the coat's bihemispherical albedo, 2 ∫ E_spec(μ) μ dμ with E_spec the
    // specular lobe's directional albedo. A table over roughness in [0, 1] and ior in
    // [1, 3], built once on first use (about 30 ms) by stratified visible-normal
    // sampling; bilinear in (roughness, √(ior − 1)), within 0.002 of a fine quadrature.
    static float specular_albedo(float roughness, float ior);
    float distribution(Vec3f h) const;  // D(h), GGX
    float smith_g1(Vec3f w) const;      // G1(w), GGX
    // A microfacet normal from the distribution of normals visible from wo (Heitz 2018).
    Vec3f sample_visible_normal(Vec3f wo, float u1, float u2) const;

  private:
    // The coat's lobe alone (no base), for specular_albedo's table.
    struct LobeOnly {};
    BsdfCoated(LobeOnly, float roughness, float ior)
        : m_alpha(std::max(min_alpha, roughness * roughness)), m_eta(ior) {}
    static constexpr float min_alpha = 1e-3f;  // below this the lobe is a delta in float

    // Terms that depend on wo only, computed once per wo: a BSDF is built per hit and
    // eval/pdf/sample are called several times with the same wo. Not thread-safe (a BSDF
    // is a per-hit local value).
    struct WoTerms {
        float cos_o = -2, F_o = 0, G1_o = 0, p_spec = 0;
    };
    const WoTerms &wo_terms(Vec3f wo) const;
    float specular_probability(Vec3f wo) const { return wo_terms(wo).p_spec; }
    mutable WoTerms m_wo;

    Rgb m_colour, m_rho;
    Rgb m_base_scale;  // ρ / (π η² (1 − ρ F̄_int)), per channel (the constructor)
    float m_alpha, m_eta;
};

static_assert(Bsdf<BsdfCoated>);

}  // namespace pelage::renderer
