// The hair/fur BSDF of Chiang, Bitterli, Tappan, Burley 2016, "A Practical and
// Controllable Hair and Fur Model for Production Path Tracing", Computer Graphics Forum
// 35(2):275–283 (Eurographics 2016), doi:10.1111/cgf.12830 — the model of pbrt-v3/v4's
// HairBxDF and Cycles' Principled Hair (Chiang). Lobes R, TT, TRT and a residual (p_max =
// 3); longitudinal scattering M_p from d'Eon et al. 2011 in its low-roughness-stable
// (log-space) form; azimuthal scattering N_p a trimmed logistic; cuticle tilt α.
//
// Frame (pbrt's convention, stated once here):
//   * +x runs along the fibre from root to tip (the curve tangent; the cuticle tilt α
//     shifts R towards −x, TT and TRT towards +x). sin θ = w.x is the longitudinal
//     angle, φ = atan2(w.z, w.y) the azimuth around the fibre.
//   * +z is the curve's shading normal (facing the incoming ray for a ribbon / the
//     direction from the axis to the hit for a round curve), y = z × x.
//   * h ∈ [-1, 1] is the offset across the fibre where the ray hits it (h = sin γ_o):
//     h = 0 at the axis, ±1 at the silhouettes. It is constant for one hit.
// It is a Bsdf (renderer/bsdf/bsdf.h) and shares its conventions:
//   * eval(wo, wi) returns f WITHOUT the |cos θ_i| factor, where cos θ_i = wi.z.
//   Internally
//     f = S(wo, wi) / |wi.z|, S = Σ_p M_p A_p N_p the fibre scattering function, so the
//     path tracer's |wi.z| cancels and throughput gets S exactly (as in pbrt).
//   * pdf(wo, wi) is the solid-angle density of sample().
//   * sample() returns nullopt for "no sample" (never a zero pdf); its weight is
//     f·|cos θ_i|/pdf. wo and wi point away from the fibre.
// Unlike the renderer's built-in BSDFs it is two-sided and transmissive: wo and wi may
// lie on either side of z (TT sends light through the fibre), so an integrator must not
// reject wi.z < 0 and should offset the next ray along wi, not along the normal. h's sign
// matters (R reflects towards φ_o − 2γ_o): for a round curve, compute it with offset_h(x,
// n, wo) below from the cylinder normal n at the hit; z itself may be any unit vector ⊥ x
// (the model uses only φ_i − φ_o), as long as the integrator's cosine uses it. σ_a is per
// fibre radius (see hair_pigments.h to build it from melanin or colour). HairBsdf is an
// immutable value type: all methods are const and thread-safe; build one per hit (the
// constructor precomputes v_p, s and the tilt terms, ~100 ns).
#pragma once

#include <array>
#include <concepts>
#include <optional>
#include <string>

#include "renderer/bsdf/bsdf.h"

namespace pelage::renderer {

// The model's parameters; HairBsdf::validate() checks their ranges.
struct HairParams {
    float beta_m = 0.3f;       // longitudinal roughness, (0, 1]
    float beta_n = 0.3f;       // azimuthal roughness, (0, 1]
    float alpha = 0.0349066f;  // cuticle tilt in radians (default 2°), |alpha| < π/4
    float eta = 1.55f;         // index of refraction of the fibre (keratin), >= 1
    Rgb sigma_a{};             // absorption per fibre radius, each channel >= 0

    // σ_a from eumelanin/pheomelanin concentrations (d'Eon et al. 2011, hair_pigments.h).
    static HairParams from_melanin(float eumelanin, float pheomelanin, float beta_m,
                                   float beta_n);
    // σ_a from a target colour (Chiang et al. 2016 §4.2, hair_pigments.h).
    static HairParams from_colour(Rgb colour, float beta_m, float beta_n);
};

class HairBsdf {
  public:
    static constexpr int p_max = 3;

    // Precondition: validate(params, h) passes. The constructor runs at every strand hit,
    // so it only DCHECKs this; callers validate parameters once, where they come in
    // (renderer/geometry/fur_geometry.cpp per fur layer; h from offset_h() is in range).
    HairBsdf(const HairParams &params, float h);

    // The far-field model of a fibre narrower than the footprint that sees it: the
    // near-field model averaged over the offset h across the whole width,
    // S̄(wo, wi) = ½ ∫ S(wo, wi; h) dh (d'Eon, Francois, Hill, Letteri & Aubry 2011 §4;
    // Zinke & Weber 2007's far-field BCSDF; Huang et al. 2022 switch to it below the
    // pixel). A ray that meets a sub-pixel strand lands at a uniformly distributed h, so
    // the average is what the near-field model converges to over the pixel's samples,
    // without the variance of one h per sample: R's Fresnel term alone runs from 0.04 at
    // the axis to 1 at the silhouettes. The integral is taken on `nodes` strata of h,
    // one point each at the same offset ξ ∈ [0, 1) in its stratum (h_k = −1 + 2(k+ξ)/n):
    // with ξ uniform the average is unbiased, and sample() picks a stratum uniformly and
    // samples the near-field model there, so pdf() is the same average of the strata's
    // densities and the pair stays exact for MIS. M_p does not depend on h and is
    // evaluated once.
    struct FarField {
        int nodes;  // 1 ... max_nodes
        float xi;   // in [0, 1)
    };
    static constexpr int max_nodes = 16;
    HairBsdf(const HairParams &params, FarField far);

    // The first invalid argument as "HairBsdf: name = value: expected range", or "" when
    // all are valid: h ∉ [-1, 1], beta_m/beta_n ∉ (0, 1], sigma_a < 0 or not finite,
    // eta < 1 or not finite, |alpha| >= π/4.
    static std::string invalid(const HairParams &params, float h);
    // Throws std::invalid_argument with invalid()'s message when it is not "".
    static void validate(const HairParams &params, float h);

    Rgb eval(Vec3f wo, Vec3f wi) const;
    float pdf(Vec3f wo, Vec3f wi) const;
    // f and pdf from one evaluation (the integrator's light samples need both).
    Rgb eval_pdf(Vec3f wo, Vec3f wi, float *pdf) const;
    // u_lobe picks the lobe (then is reused for N_p); u1, u2 sample M_p. All in [0, 1).
    std::optional<BsdfSample> sample(Vec3f wo, float u_lobe, float u1, float u2) const;
    // Σ_p A_p at normal incidence (θ_o = 0) and this h (the far-field model: its mean
    // over h): a colour for AOVs / albedo passes.
    Rgb albedo() const;

    const HairParams &params() const { return m_params; }
    float h() const { return m_h; }
    int nodes() const { return m_nodes; }  // 1: the near-field model at h()

    // The model's pieces, exposed for tests.
    // Attenuation A_p (p = 0..p_max) for sin θ_o, at h() (near field).
    std::array<Rgb, p_max + 1> attenuation(float sin_theta_o) const {
        return attenuation(sin_theta_o, m_h);
    }
    std::array<Rgb, p_max + 1> attenuation(float sin_theta_o, float h) const;
    // Lobe selection probabilities at h(): A_p channel means, normalised (all 0 if A is
    // black).
    std::array<float, p_max + 1> lobe_pdf(float sin_theta_o) const {
        return lobe_pdf(sin_theta_o, m_h);
    }
    std::array<float, p_max + 1> lobe_pdf(float sin_theta_o, float h) const;

  private:
    // f and/or pdf (null pointers are skipped) sharing A_p, M_p and N_p.
    void evaluate(Vec3f wo, Vec3f wi, Rgb *f, float *pdf) const;
    // The offset of stratum k (far field), or h() (near field).
    float node_h(int k) const {
        return m_nodes == 1 ? m_h : -1 + 2 * (float(k) + m_xi) / float(m_nodes);
    }

    HairParams m_params;
    float m_h, m_gamma_o;
    int m_nodes = 1;
    float m_xi = 0;
    std::array<float, p_max + 1> m_v;  // M_p variance per lobe
    std::array<bool, p_max + 1>
        m_mp_log_space;  // M_p normalisation per lobe (v <= 0.1: log)
    std::array<float, p_max + 1> m_mp_scale;
    float m_s;                            // N_p logistic scale
    float m_inv_trim;                     // 1/(CDF(π) − CDF(−π)) of that logistic
    std::array<float, 3> m_sin_2k_alpha;  // sin(2^k α), k = 0, 1, 2
    std::array<float, 3> m_cos_2k_alpha;
};

static_assert(Bsdf<HairBsdf>);

// h = sin(φ_o − φ_n) = x·(n × wo) / |wo projected ⊥ x|, for the fibre tangent x, the
// cylinder's outward unit normal n at the hit (⊥ x) and wo, all in one frame (e.g.
// world), clamped to [−1, 1]. With it, R's mirror direction about n lands on Φ(0) =
// −2γ_o.
float offset_h(Vec3f x, Vec3f n, Vec3f wo);

// M_p, d'Eon et al. 2011 as written by Chiang et al. 2016: normalised so that
// ∫ M_p cos θ_i dθ_i = 1; log-space Bessel I0 for v <= 0.1. Symmetric in (i, o).
float longitudinal_scattering(float cos_theta_i, float cos_theta_o, float sin_theta_i,
                              float sin_theta_o, float v);
// Unpolarised Fresnel reflectance of a dielectric interface (from outside, IOR eta).
float fresnel_dielectric(float cos_theta_i, float eta);

}  // namespace pelage::renderer
