#include "renderer/bsdf/bsdf_coated.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "renderer/core/sampling.h"

namespace pelage::renderer {

BsdfCoated::BsdfCoated(Rgb colour, float roughness, float ior, float F_int, float S)
    : m_colour(colour), m_alpha(std::max(min_alpha, roughness * roughness)), m_eta(ior) {
    // The base albedo ρ whose BSDF reflects `colour` (file header): g from the colour,
    // then ρ = g / (1 − F̄_int + g F̄_int), the inverse of g(ρ). The base term's scale
    // ρ / (π η² (1 − ρ F̄_int)) is then g / (π η² (1 − F̄_int)).
    const float F_ext = 1 - ior * ior * (1 - F_int);
    const float inv_T = 1 / (1 - F_ext);
    const Rgb g{std::clamp((colour.x - S) * inv_T, 0.0f, 1.0f),
                std::clamp((colour.y - S) * inv_T, 0.0f, 1.0f),
                std::clamp((colour.z - S) * inv_T, 0.0f, 1.0f)};
    m_rho = {g.x / (1 - F_int + g.x * F_int), g.y / (1 - F_int + g.y * F_int),
             g.z / (1 - F_int + g.z * F_int)};
    m_base_scale = g * (inv_pi / (ior * ior * (1 - F_int)));
}

float BsdfCoated::specular_albedo(float roughness, float ior) {
    // Rows: roughness 0, 1/32 ... 1; columns: u = √(ior − 1) from 0 to √2 in 16 steps
    // (the albedo changes fastest just above ior 1).
    constexpr int nr = 32, nu = 16, n_mu = 16, n_h = 8;
    static const float u_max = std::sqrt(2.0f);
    static const std::array<float, (nr + 1) * (nu + 1)> table = [] {
        std::array<float, (nr + 1) * (nu + 1)> t{};
        for (int i = 0; i <= nr; ++i)
            for (int j = 0; j <= nu; ++j) {
                const float u = u_max * float(j) / nu;
                const BsdfCoated b(LobeOnly{}, float(i) / nr, 1 + u * u);
                // S̄ = 2 ∫ E(μ) μ dμ, midpoint rule in μ; E(μ) by visible-normal
                // sampling on an n_h × n_h grid, whose weight for the specular lobe is
                // F(wo·h) G1(wi) (Heitz 2018 §2).
                double S = 0;
                for (int a = 0; a < n_mu; ++a) {
                    const float mu = (float(a) + 0.5f) / n_mu;
                    const Vec3f wo{std::sqrt(1 - mu * mu), 0, mu};
                    double E = 0;
                    for (int p = 0; p < n_h; ++p)
                        for (int q = 0; q < n_h; ++q) {
                            const Vec3f h = b.sample_visible_normal(
                                wo, (float(p) + 0.5f) / n_h, (float(q) + 0.5f) / n_h);
                            const Vec3f wi = h * (2 * dot(wo, h)) - wo;
                            if (wi.z <= 0) continue;
                            E += fresnel_dielectric(dot(wo, h), b.m_eta) * b.smith_g1(wi);
                        }
                    S += 2 * mu * E / (n_h * n_h) / n_mu;
                }
                t[size_t(i * (nu + 1) + j)] = float(S);
            }
        return t;
    }();
    const float x = std::clamp(roughness, 0.0f, 1.0f) * nr;
    const float y = std::sqrt(std::clamp(ior, 1.0f, 3.0f) - 1) * (nu / u_max);
    const int i = std::min(int(x), nr - 1), j = std::min(int(y), nu - 1);
    const float fx = x - float(i), fy = y - float(j);
    auto at = [&](int r, int c) { return table[size_t(r * (nu + 1) + c)]; };
    return (at(i, j) * (1 - fx) + at(i + 1, j) * fx) * (1 - fy) +
           (at(i, j + 1) * (1 - fx) + at(i + 1, j + 1) * fx) * fy;
}

float BsdfCoated::internal_diffuse_reflectance(float eta) {
    // F̄_ext = 2 ∫_0^1 F(μ) μ dμ by the midpoint rule; F is smooth, 1024 points give
    // ~1e-6.
    constexpr int n = 1024;
    double F_ext = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        F_ext += 2 * fresnel_dielectric(float(mu), eta) * mu / n;
    }
    return float(1 - (1 - F_ext) / (double(eta) * eta));
}

float BsdfCoated::internal_diffuse_reflectance_table(float eta) {
    // Sampled uniformly in u = sqrt(eta - 1): F̄_int rises steeply just above 1 and
    // evenly in u, where linear interpolation is then accurate.
    constexpr int n = 256;
    static const float u_max = std::sqrt(2.0f);
    static const std::array<float, n + 1> table = [] {
        std::array<float, n + 1> t{};
        for (int i = 0; i <= n; ++i) {
            const float u = u_max * float(i) / n;
            t[i] = internal_diffuse_reflectance(1 + u * u);
        }
        return t;
    }();
    const float x = std::sqrt(std::clamp(eta, 1.0f, 3.0f) - 1) * (n / u_max);
    const int i = std::min(int(x), n - 1);
    return table[i] + (table[i + 1] - table[i]) * (x - float(i));
}

float BsdfCoated::fresnel_dielectric(float cos_i, float eta) {
    cos_i = std::clamp(cos_i, 0.0f, 1.0f);
    const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1.0f;
    const float cos_t = std::sqrt(1 - sin2_t);
    const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

float BsdfCoated::distribution(Vec3f h) const {
    if (h.z <= 0) return 0.0f;
    const float a2 = m_alpha * m_alpha;
    const float d = h.z * h.z * (a2 - 1) + 1;
    return a2 / (pi * d * d);
}

float BsdfCoated::smith_g1(Vec3f w) const {
    if (w.z <= 0) return 0.0f;
    const float tan2 = (1 - w.z * w.z) / (w.z * w.z);
    return 2 / (1 + std::sqrt(1 + m_alpha * m_alpha * tan2));
}

const BsdfCoated::WoTerms &BsdfCoated::wo_terms(Vec3f wo) const {
    if (m_wo.cos_o == wo.z) return m_wo;
    m_wo.cos_o = wo.z;
    m_wo.F_o = fresnel_dielectric(wo.z, m_eta);
    m_wo.G1_o = smith_g1(wo);
    // Pick the coat in proportion to its reflectance, but never starve either lobe.
    const float base = luminance(m_rho) * (1 - m_wo.F_o);
    m_wo.p_spec = std::clamp(m_wo.F_o / std::max(m_wo.F_o + base, 1e-6f), 0.1f, 0.9f);
    return m_wo;
}

Rgb BsdfCoated::eval_pdf(Vec3f wo, Vec3f wi, float *pdf_out) const {
    if (wo.z <= 0 || wi.z <= 0) {
        *pdf_out = 0;
        return {};
    }
    const Vec3f h = normalize(wo + wi);
    const WoTerms &o = wo_terms(wo);
    const float D = distribution(h);
    // Visible-normal density D_wo(h) = G1(wo) max(0, wo·h) D(h) / cos θ_o, then the
    // reflection Jacobian 1 / (4 wo·h).
    const float pdf_spec = o.G1_o * D / (4 * wo.z);
    *pdf_out = o.p_spec * pdf_spec + (1 - o.p_spec) * wi.z * inv_pi;
    const float f_h = fresnel_dielectric(dot(wo, h), m_eta);
    const float spec = f_h * D * o.G1_o * smith_g1(wi) / (4 * wo.z * wi.z);
    const float t = (1 - fresnel_dielectric(wi.z, m_eta)) * (1 - o.F_o);
    return m_base_scale * t + Rgb{spec, spec, spec};
}

Rgb BsdfCoated::eval(Vec3f wo, Vec3f wi) const {
    float pdf_unused;
    return eval_pdf(wo, wi, &pdf_unused);
}

float BsdfCoated::pdf(Vec3f wo, Vec3f wi) const {
    if (wo.z <= 0 || wi.z <= 0) return 0.0f;
    const Vec3f h = normalize(wo + wi);
    const WoTerms &o = wo_terms(wo);
    const float pdf_spec = o.G1_o * distribution(h) / (4 * wo.z);
    return o.p_spec * pdf_spec + (1 - o.p_spec) * wi.z * inv_pi;
}

Vec3f BsdfCoated::sample_visible_normal(Vec3f wo, float u1, float u2) const {
    // Heitz 2018, listing 1: stretch wo, sample the projected disc, unstretch.
    const Vec3f vh = normalize(Vec3f{m_alpha * wo.x, m_alpha * wo.y, wo.z});
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3f t1 = len2 > 0 ? Vec3f{-vh.y, vh.x, 0} / std::sqrt(len2) : Vec3f{1, 0, 0};
    const Vec3f t2 = cross(vh, t1);
    const float r = std::sqrt(u1);
    float sin_phi, cos_phi;
    sin_cos_turn(u2, &sin_phi, &cos_phi);  // φ = 2π u2
    const float p1 = r * cos_phi;
    float p2 = r * sin_phi;
    const float s = 0.5f * (1 + vh.z);
    p2 = (1 - s) * std::sqrt(std::max(0.0f, 1 - p1 * p1)) + s * p2;
    const Vec3f nh =
        t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2));
    return normalize(Vec3f{m_alpha * nh.x, m_alpha * nh.y, std::max(1e-6f, nh.z)});
}

std::optional<BsdfSample> BsdfCoated::sample(Vec3f wo, float u_lobe, float u1,
                                             float u2) const {
    if (wo.z <= 0) return std::nullopt;
    Vec3f wi;
    if (u_lobe < specular_probability(wo)) {
        const Vec3f h = sample_visible_normal(wo, u1, u2);
        wi = h * (2 * dot(wo, h)) - wo;
    } else {
        wi = sample_cosine_hemisphere(u1, u2);
    }
    if (wi.z <= 0) return std::nullopt;
    float pdf_wi;
    const Rgb f = eval_pdf(wo, wi, &pdf_wi);
    if (!(pdf_wi > 0)) return std::nullopt;
    return BsdfSample{wi, f, pdf_wi, f * (wi.z / pdf_wi), false};
}

}  // namespace pelage::renderer
