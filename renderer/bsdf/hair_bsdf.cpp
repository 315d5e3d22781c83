// Chiang, Bitterli, Tappan, Burley 2016, doi:10.1111/cgf.12830 — see hair_bsdf.h for the
// frame and conventions. The structure follows pbrt-v4's HairBxDF (the paper's reference
// implementation guide is pbrt's "The Implementation of a Hair Scattering Model").
#include "renderer/bsdf/hair_bsdf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "renderer/bsdf/hair_pigments.h"
#include "sim/core/check.h"

namespace pelage::renderer {
namespace {

constexpr float two_pi = 2 * pi;
// Below this cos θ_o the modified index η' = sqrt(η² − sin²θ_o)/cos θ_o is clamped
// finite.
constexpr float min_cos_theta = 1e-7f;
constexpr float ln_2 = 0.693147181f;

// The model reads sin θ and cos θ off a direction's components, so directions must be
// unit length (to float rounding).
[[maybe_unused]] bool is_unit(Vec3f w) { return std::abs(dot(w, w) - 1) <= 1e-3f; }

std::string bad(const std::string &name, float value, const char *expected) {
    return "HairBsdf: " + name + " = " + std::to_string(value) + ": " + expected;
}

// Modified Bessel function of the first kind, order 0, by its power series
// Σ_k (x²/4)^k / (k!)², summed in double until the terms stop mattering (used for
// x <= 12). Deviates from pbrt, which stops after 10 terms: that underestimates I0 by
// 0.3 % at x = 10 and 2 % at x = 12 (for x <= 12, 40 terms reach 1e-8), and the lost
// M_p mass would leave the pdf integral short of 1 (PdfIntegratesToOne).
float bessel_i0(float x) {
    // 1/k², so the recurrence is a chain of multiplies, not divides
    static constexpr auto inv_k2 = [] {
        std::array<double, 40> t{};
        for (int k = 1; k < 40; ++k) t[k] = 1.0 / (double(k) * k);
        return t;
    }();
    const double q = 0.25 * double(x) * double(x);
    double term = 1, sum = 1;
    for (int k = 1; k < 40 && term > 1e-8 * sum; ++k) {
        term *= q * inv_k2[k];
        sum += term;
    }
    return static_cast<float>(sum);
}

// log I0(x); above 12, the asymptotic expansion
// I0(x) ≈ e^x / sqrt(2πx) · (1 + 1/(8x) + 9/(128x²) + 225/(3072x³)) (relative error <
// 1e-5) keeps M_p finite for tiny v.
float log_bessel_i0(float x) {
    if (x > 12) {
        const float r = 1 / x;
        return x - 0.5f * std::log(two_pi * x) +
               std::log1p(r * (1.0f / 8 + r * (9.0f / 128 + r * (225.0f / 3072))));
    }
    return std::log(bessel_i0(x));
}

float logistic(float x, float s) {
    x = std::abs(x);
    const float e = std::exp(-x / s);
    return e / (s * sqr(1 + e));
}

float logistic_cdf(float x, float s) { return 1 / (1 + std::exp(-x / s)); }

// Inverse CDF of the logistic trimmed to [a, b].
float sample_trimmed_logistic(float u, float s, float a, float b) {
    const float k = logistic_cdf(b, s) - logistic_cdf(a, s);
    const float x = -s * std::log(1 / (u * k + logistic_cdf(a, s)) - 1);
    return std::clamp(x, a, b);
}

// Φ(p, γ_o, γ_t) = 2pγ_t − 2γ_o + pπ: the azimuthal deflection of lobe p.
float azimuthal_deflection(int p, float gamma_o, float gamma_t) {
    return 2 * p * gamma_t - 2 * gamma_o + p * pi;
}

// Geometry of the refracted path shared by eval, pdf and sample.
struct Refraction {
    float sin_theta_o, cos_theta_o, gamma_t, cos_theta_t, cos_gamma_t;
};

Refraction refract(float sin_theta_o, float eta, float h) {
    Refraction r;
    r.sin_theta_o = std::clamp(sin_theta_o, -1.0f, 1.0f);
    r.cos_theta_o = safe_sqrt(1 - sqr(r.sin_theta_o));
    const float sin_theta_t = r.sin_theta_o / eta;
    r.cos_theta_t = safe_sqrt(1 - sqr(sin_theta_t));
    // Modified index for the azimuthal (projected) refraction: η' (Bravais)
    const float etap = std::sqrt(eta * eta - sqr(r.sin_theta_o)) /
                       std::max(r.cos_theta_o, min_cos_theta);
    const float sin_gamma_t = h / etap;
    r.cos_gamma_t = safe_sqrt(1 - sqr(sin_gamma_t));
    r.gamma_t = safe_asin(sin_gamma_t);
    return r;
}

}  // namespace

float fresnel_dielectric(float cos_theta_i, float eta) {
    cos_theta_i = std::clamp(cos_theta_i, -1.0f, 1.0f);
    if (cos_theta_i < 0) {  // leaving the dielectric
        eta = 1 / eta;
        cos_theta_i = -cos_theta_i;
    }
    const float sin2_theta_t = (1 - sqr(cos_theta_i)) / sqr(eta);
    if (sin2_theta_t >= 1) return 1;  // total internal reflection
    const float cos_theta_t = safe_sqrt(1 - sin2_theta_t);
    const float r_parl =
        (eta * cos_theta_i - cos_theta_t) / (eta * cos_theta_i + cos_theta_t);
    const float r_perp =
        (cos_theta_i - eta * cos_theta_t) / (cos_theta_i + eta * cos_theta_t);
    return (sqr(r_parl) + sqr(r_perp)) / 2;
}

namespace {

// M_p's normalisation 1/(2v sinh(1/v)), or its logarithm when v <= 0.1: there sinh(1/v)
// and I0(a) overflow float, so M_p is evaluated as exp(log I0(a) − b + log_scale) with
// sinh(1/v) ≈ e^{1/v}/2 (relative error e^{−2/v} <= 2e-9). pbrt writes ln 2 as 0.6931,
// 5e-5 low; we use the full value. Depends on v only: HairBsdf precomputes it per lobe.
struct MpNorm {
    bool log_space;
    float scale;  // log_space ? −1/v + ln 2 + ln(1/(2v)) : 1/(2v sinh(1/v))
};

MpNorm mp_norm(float v) {
    if (v <= 0.1f) return {true, -1 / v + ln_2 + std::log(1 / (2 * v))};
    return {false, 1 / (std::sinh(1 / v) * 2 * v)};
}

float mp_eval(float cos_theta_i, float cos_theta_o, float sin_theta_i, float sin_theta_o,
              float v, MpNorm n) {
    const float a = cos_theta_i * cos_theta_o / v;
    const float b = sin_theta_i * sin_theta_o / v;
    if (n.log_space) return std::exp(log_bessel_i0(a) - b + n.scale);
    return std::exp(-b) * bessel_i0(a) * n.scale;
}

// N_p with the trimmed logistic's normalisation 1/(CDF(π) − CDF(−π)) precomputed.
float np_eval(float phi, int p, float s, float inv_trim, float gamma_o, float gamma_t) {
    // Remap Δφ to [−π, π]
    const float dphi =
        std::remainder(phi - azimuthal_deflection(p, gamma_o, gamma_t), two_pi);
    return logistic(dphi, s) * inv_trim;
}

}  // namespace

float longitudinal_scattering(float cos_theta_i, float cos_theta_o, float sin_theta_i,
                              float sin_theta_o, float v) {
    return mp_eval(cos_theta_i, cos_theta_o, sin_theta_i, sin_theta_o, v, mp_norm(v));
}

float offset_h(Vec3f x, Vec3f n, Vec3f wo) {
    const Vec3f n_cross_wo = cross(n, wo);
    const Vec3f wo_perp = wo - x * dot(wo, x);
    const float len = length(wo_perp);
    if (!(len > 0)) return 0;  // wo along the fibre: every h sees the same geometry
    return std::clamp(dot(x, n_cross_wo) / len, -1.0f, 1.0f);
}

HairParams HairParams::from_melanin(float eumelanin, float pheomelanin, float beta_m,
                                    float beta_n) {
    HairParams p;
    p.beta_m = beta_m;
    p.beta_n = beta_n;
    p.sigma_a = sigma_a_from_melanin(eumelanin, pheomelanin);
    return p;
}

HairParams HairParams::from_colour(Rgb colour, float beta_m, float beta_n) {
    HairParams p;
    p.beta_m = beta_m;
    p.beta_n = beta_n;
    p.sigma_a = sigma_a_from_colour(colour, beta_n);
    return p;
}

std::string HairBsdf::invalid(const HairParams &params, float h) {
    if (!(h >= -1 && h <= 1)) return bad("h", h, "must be in [-1, 1]");
    if (!(params.beta_m > 0 && params.beta_m <= 1))
        return bad("beta_m", params.beta_m, "must be in (0, 1]");
    if (!(params.beta_n > 0 && params.beta_n <= 1))
        return bad("beta_n", params.beta_n, "must be in (0, 1]");
    if (!(std::abs(params.alpha) < pi / 4))
        return bad("alpha", params.alpha, "must be in (-pi/4, pi/4) radians");
    if (!(params.eta >= 1 && std::isfinite(params.eta)))
        return bad("eta", params.eta, "must be finite and >= 1");
    for (int c = 0; c < 3; ++c)
        if (!(params.sigma_a[c] >= 0 && std::isfinite(params.sigma_a[c])))
            return bad("sigma_a[" + std::to_string(c) + "]", params.sigma_a[c],
                       "must be finite and >= 0");
    return {};
}

void HairBsdf::validate(const HairParams &params, float h) {
    if (std::string e = invalid(params, h); !e.empty()) throw std::invalid_argument(e);
}

HairBsdf::HairBsdf(const HairParams &params, float h) : m_params(params), m_h(h) {
    PELAGE_DCHECK(invalid(params, h).empty());

    m_gamma_o = safe_asin(h);

    // --- Longitudinal variance v_p from beta_m (Chiang et al. 2016 fit; TT is narrower
    // (v/4) and TRT wider (4v) than R) ---
    const float bm = params.beta_m;
    m_v[0] = sqr(0.726f * bm + 0.812f * sqr(bm) + 3.7f * std::pow(bm, 20.0f));
    m_v[1] = 0.25f * m_v[0];
    m_v[2] = 4 * m_v[0];
    m_v[3] = m_v[2];
    for (int p = 0; p <= p_max; ++p) {
        const MpNorm n = mp_norm(m_v[p]);
        m_mp_log_space[p] = n.log_space;
        m_mp_scale[p] = n.scale;
    }

    // --- Azimuthal logistic scale s from beta_n (Chiang et al. 2016 fit) ---
    const float bn = params.beta_n;
    m_s = std::sqrt(pi / 8) *
          (0.265f * bn + 1.194f * sqr(bn) + 5.372f * std::pow(bn, 22.0f));
    m_inv_trim = 1 / (logistic_cdf(pi, m_s) - logistic_cdf(-pi, m_s));

    // --- Cuticle tilt: sin/cos of α, 2α, 4α ---
    m_sin_2k_alpha[0] = std::sin(params.alpha);
    m_cos_2k_alpha[0] = safe_sqrt(1 - sqr(m_sin_2k_alpha[0]));
    for (int k = 1; k < 3; ++k) {
        m_sin_2k_alpha[k] = 2 * m_cos_2k_alpha[k - 1] * m_sin_2k_alpha[k - 1];
        m_cos_2k_alpha[k] = sqr(m_cos_2k_alpha[k - 1]) - sqr(m_sin_2k_alpha[k - 1]);
    }
}

HairBsdf::HairBsdf(const HairParams &params, FarField far) : HairBsdf(params, 0.0f) {
    PELAGE_DCHECK(far.nodes >= 1 && far.nodes <= max_nodes && far.xi >= 0 && far.xi < 1);
    m_nodes = std::clamp(far.nodes, 1, max_nodes);
    m_xi = std::clamp(far.xi, 0.0f, 0x1.fffffep-1f);
    if (m_nodes == 1) m_h = -1 + 2 * m_xi, m_gamma_o = safe_asin(m_h);
}

namespace {

// θ_o rotated by the cuticle tilt for lobe p, so that M_p, which peaks at θ_i = −θ_o',
// puts R at θ_i = −θ_o − 2α (towards the root), TT at −θ_o + α and TRT at −θ_o + 4α
// (towards the tip), +x running from root to tip. That is the shift of Marschner et al.
// 2003 §4.1 (the scales' free edges point to the tip, so their normals lean towards the
// root) with Chiang et al. 2016's −2α, α, 4α, and what Cycles' Principled Hair does.
// Deviates from pbrt-v3/v4, which rotate θ_o by −2α, +α, +4α and so shift every lobe
// the other way (CuticleTiltShiftsRTowardsTheRootAndTtTrtTowardsTheTip). The residual
// is not tilted. Returns {sin θ_o', |cos θ_o'|}.
struct Tilted {
    float sin_theta, cos_theta;
};

Tilted tilt(int p, float sin_o, float cos_o, const std::array<float, 3> &sin_2k,
            const std::array<float, 3> &cos_2k) {
    float s = sin_o, c = cos_o;
    if (p == 0) {  // θ_o + 2α
        s = sin_o * cos_2k[1] + cos_o * sin_2k[1];
        c = cos_o * cos_2k[1] - sin_o * sin_2k[1];
    } else if (p == 1) {  // θ_o − α
        s = sin_o * cos_2k[0] - cos_o * sin_2k[0];
        c = cos_o * cos_2k[0] + sin_o * sin_2k[0];
    } else if (p == 2) {  // θ_o − 4α
        s = sin_o * cos_2k[2] - cos_o * sin_2k[2];
        c = cos_o * cos_2k[2] + sin_o * sin_2k[2];
    }
    return {s, std::abs(c)};
}

// A_p for the refraction r at offset h (HairBsdf::attenuation).
std::array<Rgb, HairBsdf::p_max + 1> attenuation_of(const Refraction &r, float h,
                                                    const HairParams &params) {
    constexpr int p_max = HairBsdf::p_max;
    // Transmittance of one chord through the fibre: T = exp(−σ_a · 2 cos γ_t / cos θ_t)
    const Rgb T = exp(params.sigma_a * (-2 * r.cos_gamma_t / r.cos_theta_t));
    const float cos_gamma_o = safe_sqrt(1 - sqr(h));
    const float f = fresnel_dielectric(r.cos_theta_o * cos_gamma_o, params.eta);
    std::array<Rgb, p_max + 1> a;
    // R reflects once; TT transmits twice; each further bounce adds T·f
    a[0] = Rgb{f, f, f};
    a[1] = (sqr(1 - f)) * T;
    for (int p = 2; p < p_max; ++p) a[p] = a[p - 1] * T * f;
    // Residual: the geometric series of all higher bounces, A_{p_max} =
    // A_{p_max−1}·f·T/(1 − f·T)
    for (int c = 0; c < 3; ++c) {
        const float tf = T[c] * f, denom = 1 - tf;
        const float v = denom > 0 ? a[p_max - 1][c] * tf / denom : 0.0f;
        (c == 0 ? a[p_max].x : (c == 1 ? a[p_max].y : a[p_max].z)) = v;
    }
    return a;
}

}  // namespace

std::array<Rgb, HairBsdf::p_max + 1> HairBsdf::attenuation(float sin_theta_o,
                                                           float h) const {
    return attenuation_of(refract(sin_theta_o, m_params.eta, h), h, m_params);
}

namespace {

// A lobe is chosen in proportion to the mean of its attenuation's channels, not its
// luminance (pbrt's choice): a sampled lobe's weight is A_p / w_p, and pheomelanin fur
// transmits red far more than blue (TT at h = 0: 0.30, 0.086, 0.002), so luminance, which
// weighs red by 0.21, lets a red-heavy lobe's red weight reach 1 / 0.21 = 4.7 per bounce;
// the mean caps it at 3, which shortens the red fireflies of multi-bounce fur paths.
float selection_weight(const Rgb &a) { return std::max((a.x + a.y + a.z) / 3, 0.0f); }

}  // namespace

std::array<float, HairBsdf::p_max + 1> HairBsdf::lobe_pdf(float sin_theta_o,
                                                          float h) const {
    const auto a = attenuation(sin_theta_o, h);
    std::array<float, p_max + 1> w{};
    float sum = 0;
    for (int p = 0; p <= p_max; ++p) sum += (w[p] = selection_weight(a[p]));
    if (!(sum > 0)) return {};
    for (float &x : w) x /= sum;
    return w;
}

Rgb HairBsdf::albedo() const {
    Rgb sum;
    for (int k = 0; k < m_nodes; ++k)
        for (const Rgb &a : attenuation(0, node_h(k))) sum += a;
    return m_nodes == 1 ? sum : sum / float(m_nodes);
}

void HairBsdf::evaluate(Vec3f wo, Vec3f wi, Rgb *f, float *pdf) const {
    PELAGE_DCHECK(is_unit(wo) && is_unit(wi));
    const float sin_theta_o = std::clamp(wo.x, -1.0f, 1.0f);
    const float cos_theta_o = safe_sqrt(1 - sqr(sin_theta_o));
    const float sin_theta_i = std::clamp(wi.x, -1.0f, 1.0f);
    const float cos_theta_i = safe_sqrt(1 - sqr(sin_theta_i));
    const float phi = std::atan2(wi.z, wi.y) - std::atan2(wo.z, wo.y);

    // M_p depends on the longitudinal angles only: once, for every stratum of h.
    std::array<float, p_max + 1> m;
    for (int p = 0; p <= p_max; ++p) {
        const Tilted o =
            tilt(p, sin_theta_o, cos_theta_o, m_sin_2k_alpha, m_cos_2k_alpha);
        m[p] = mp_eval(cos_theta_i, o.cos_theta, sin_theta_i, o.sin_theta, m_v[p],
                       {m_mp_log_space[p], m_mp_scale[p]});
    }

    // --- S = Σ_p M_p A_p N_p and pdf = Σ_p M_p w_p N_p, then the residual with uniform
    // N; the far field averages both over the strata of h ---
    Rgb s_sum;
    float pdf_sum = 0;
    for (int k = 0; k < m_nodes; ++k) {
        const float h = node_h(k);
        const float gamma_o = m_nodes == 1 ? m_gamma_o : safe_asin(h);
        const Refraction r = refract(wo.x, m_params.eta, h);
        const auto a = attenuation_of(r, h, m_params);
        std::array<float, p_max + 1> w{};
        if (pdf) {
            // Lobe selection probabilities, as lobe_pdf
            float sum = 0;
            for (int p = 0; p <= p_max; ++p) sum += (w[p] = selection_weight(a[p]));
            if (sum > 0)
                for (float &x : w) x /= sum;
        }
        for (int p = 0; p <= p_max; ++p) {
            const float n_p = p < p_max
                                  ? np_eval(phi, p, m_s, m_inv_trim, gamma_o, r.gamma_t)
                                  : 1 / two_pi;
            const float mn = m[p] * n_p;
            s_sum += mn * a[p];
            pdf_sum += mn * w[p];
        }
    }
    if (m_nodes > 1) {
        const float inv = 1 / float(m_nodes);
        s_sum = s_sum * inv;
        pdf_sum *= inv;
    }

    // f = S / |cos θ_i| w.r.t. the shading normal z, so the integrator's |wi.z| cancels
    if (f) {
        const float abs_cos = std::abs(wi.z);
        *f = abs_cos > 0 ? divide_exactly(s_sum, abs_cos) : Rgb{};
    }
    if (pdf) *pdf = pdf_sum;
}

Rgb HairBsdf::eval(Vec3f wo, Vec3f wi) const {
    Rgb f;
    evaluate(wo, wi, &f, nullptr);
    return f;
}

float HairBsdf::pdf(Vec3f wo, Vec3f wi) const {
    float pdf;
    evaluate(wo, wi, nullptr, &pdf);
    return pdf;
}

Rgb HairBsdf::eval_pdf(Vec3f wo, Vec3f wi, float *pdf) const {
    Rgb f;
    evaluate(wo, wi, &f, pdf);
    return f;
}

std::optional<BsdfSample> HairBsdf::sample(Vec3f wo, float u_lobe, float u1,
                                           float u2) const {
    PELAGE_DCHECK(is_unit(wo));
    // --- The far field: a stratum of h, uniformly; u_lobe rescaled for the lobe ---
    float h = m_h, gamma_o = m_gamma_o;
    if (m_nodes > 1) {
        const float scaled = u_lobe * float(m_nodes);
        const int k = std::min(int(scaled), m_nodes - 1);
        u_lobe = std::min(scaled - float(k), 0x1.fffffep-1f);
        h = node_h(k);
        gamma_o = safe_asin(h);
    }
    const Refraction r = refract(wo.x, m_params.eta, h);
    const auto w = lobe_pdf(wo.x, h);

    // --- Choose lobe p by the A_p weights; remap u_lobe to [0, 1) for reuse by N_p ---
    int p = 0;
    for (; p < p_max; ++p) {
        if (u_lobe < w[p]) break;
        u_lobe -= w[p];
    }
    if (!(w[p] > 0)) return std::nullopt;
    u_lobe = std::min(u_lobe / w[p], 0x1.fffffep-1f);

    // --- Sample M_p for θ_i: a cap around −wo' of variance v_p, projected on x ---
    const Tilted o =
        tilt(p, r.sin_theta_o, r.cos_theta_o, m_sin_2k_alpha, m_cos_2k_alpha);
    const float v = m_v[p];
    // Inverse CDF cos θ = 1 + v·ln(u + (1 − u)·e^{−2/v}); the floor only guards log(0)
    // when e^{−2/v} underflows (pbrt clamps u to 1e-5 instead, which moves that much
    // mass).
    const float cos_theta = 1 + v * std::log(std::max(u1 + (1 - u1) * std::exp(-2 / v),
                                                      std::numeric_limits<float>::min()));
    const float sin_theta = safe_sqrt(1 - sqr(cos_theta));
    const float cos_phi = std::cos(two_pi * u2);
    const float sin_theta_i = std::clamp(
        -cos_theta * o.sin_theta + sin_theta * cos_phi * o.cos_theta, -1.0f, 1.0f);
    const float cos_theta_i = safe_sqrt(1 - sqr(sin_theta_i));

    // --- Sample N_p for Δφ ---
    const float dphi = p < p_max ? azimuthal_deflection(p, gamma_o, r.gamma_t) +
                                       sample_trimmed_logistic(u_lobe, m_s, -pi, pi)
                                 : two_pi * u_lobe;
    const float phi_i = std::atan2(wo.z, wo.y) + dphi;
    const Vec3f wi{sin_theta_i, cos_theta_i * std::cos(phi_i),
                   cos_theta_i * std::sin(phi_i)};

    Rgb f;
    float pdf_wi;
    evaluate(wo, wi, &f, &pdf_wi);
    const float abs_cos = std::abs(wi.z);
    if (!(pdf_wi > 0) || !(abs_cos > 0)) return std::nullopt;
    return BsdfSample{wi, f, pdf_wi, f * (abs_cos / pdf_wi), false};
}

}  // namespace pelage::renderer
