#include "renderer/lights/lights.h"

#include <cmath>
#include <limits>

#include "renderer/core/sampling.h"

namespace pelage::renderer {

namespace {
constexpr float inf = std::numeric_limits<float>::infinity();
}

Lights::Lights(const std::vector<LightDesc> &descs, float scene_radius,
               IntegratorDesc::LightSelection selection) {
    const float disc = pi * scene_radius * scene_radius;  // the scene's cross-section
    for (const LightDesc &d : descs) {
        Light l;
        // --- Estimated power: luminance of the flux into the scene (pbrt-v4 Light::Phi)
        const float lum = luminance(d.color) * d.intensity;
        switch (d.type) {
            case LightDesc::Type::environment:
                m_power.push_back(0);  // set below, once the image is read
                break;
            case LightDesc::Type::distant:  // irradiance E across the scene's disc
                m_power.push_back(lum * disc);
                break;
            case LightDesc::Type::sphere:  // π L per unit area over 4π r²
                m_power.push_back(lum * pi * 4 * pi * d.radius * d.radius);
                break;
            case LightDesc::Type::quad:
                m_power.push_back(lum * pi * length(cross(d.edge_u, d.edge_v)) *
                                  (d.two_sided ? 2 : 1));
                break;
        }
        l.type = d.type;
        l.L = d.color * d.intensity;
        switch (d.type) {
            case LightDesc::Type::environment:
                l.env = d.image.empty() ? std::make_shared<EnvironmentLight>(l.L)
                                        : std::make_shared<EnvironmentLight>(
                                              d.image, d.intensity, d.rotation_deg);
                m_infinite.push_back(int(m_lights.size()));
                // Uniform radiance L into a sphere of radius r: 4π r² · π L.
                m_power.back() = l.env->mean_luminance() * 4 * pi * disc;
                break;
            case LightDesc::Type::distant: {
                l.to_light = -normalize(d.direction);
                l.frame = Frame::from_z(l.to_light);
                const float half = 0.5f * d.angle_deg * pi / 180;
                l.cos_max = std::cos(half);
                if (d.angle_deg > 0) l.cone_pdf = 1 / (2 * pi * (1 - l.cos_max));
                if (d.angle_deg > 0) {
                    // Irradiance E of a disc of solid angle Ω = 2π(1 − cos θ_max):
                    // uniform radiance E / Ω (the cos factor across a small disc ≈ 1).
                    l.L = l.L / (2 * pi * (1 - l.cos_max));
                    m_infinite.push_back(int(m_lights.size()));
                }
                break;
            }
            case LightDesc::Type::sphere:
                l.center = d.center;
                l.radius = d.radius;
                break;
            case LightDesc::Type::quad: {
                l.corner = d.corner;
                l.eu = d.edge_u;
                l.ev = d.edge_v;
                const Vec3f c = cross(d.edge_u, d.edge_v);
                l.area = length(c);
                l.n = c / l.area;
                l.two_sided = d.two_sided;
                break;
            }
        }
        m_lights.push_back(std::move(l));
    }
    // --- Selection probabilities and their alias table ---
    // A constant environment is never a next-event light: the direction NEE would draw
    // for it (cosine-weighted about the normal) is what the BSDF's diffuse lobe draws for
    // the continuation ray, which the path traces anyway and which, escaping, carries the
    // environment with full MIS weight (its light density is 0). Sampled as a light, it
    // costs a shadow ray per vertex and lowers the noise by less than that ray's cost.
    std::vector<double> weight(m_lights.size());
    std::vector<bool> is_nee(m_lights.size());
    double total = 0;
    for (size_t i = 0; i < m_lights.size(); ++i) {
        float &p = m_power[i];
        if (!std::isfinite(p) || p < 0) p = 0;
        const bool nee = is_nee[i] = !(m_lights[i].env && m_lights[i].env->is_constant());
        m_nee_count += nee;
        weight[i] = nee ? p : 0.0;
        total += weight[i];
    }
    m_sample_all = selection == IntegratorDesc::LightSelection::all ||
                   (selection == IntegratorDesc::LightSelection::automatic &&
                    m_nee_count <= max_sample_all);
    const bool uniform = selection == IntegratorDesc::LightSelection::uniform ||
                         !(total > 0) || !std::isfinite(total);
    for (size_t i = 0; i < m_lights.size(); ++i) {
        const bool nee = is_nee[i];
        if (uniform) weight[i] = nee ? 1.0 : 0.0;
        m_select_pdf.push_back(!nee           ? 0.0f
                               : m_sample_all ? 1.0f
                               : uniform      ? 1.0f / float(m_nee_count)
                                              : float(weight[i] / total));
    }
    if (m_nee_count > 0) build_alias_table(weight);
}

void Lights::build_alias_table(const std::vector<double> &weights) {
    // Vose's algorithm: scale the weights to a mean of 1; repeatedly fill a bin below 1
    // (small) from one above (large), which keeps the remainder. Bins left over hold
    // exactly 1 up to rounding and keep their own light.
    const size_t n = weights.size();
    m_alias.assign(n, AliasBin{1.0f, 0});
    if (n == 0) return;
    double sum = 0;
    for (double w : weights) sum += w;
    std::vector<double> scaled(n);
    std::vector<size_t> small, large;
    for (size_t i = 0; i < n; ++i) {
        scaled[i] = weights[i] * double(n) / sum;
        m_alias[i].other = int(i);
        (scaled[i] < 1 ? small : large).push_back(i);
    }
    while (!small.empty() && !large.empty()) {
        const size_t s = small.back(), l = large.back();
        small.pop_back();
        m_alias[s] = {float(scaled[s]), int(l)};
        scaled[l] -= 1 - scaled[s];
        if (scaled[l] < 1) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // Rounding can leave a bin short of 1 with no large bin to fill it; it keeps its
    // own light, unless that light has no weight at all (it must never be chosen).
    size_t heaviest = 0;
    for (size_t i = 1; i < n; ++i)
        if (weights[i] > weights[heaviest]) heaviest = i;
    for (size_t i : small) m_alias[i] = {1.0f, int(i)};
    for (size_t i : large) m_alias[i] = {1.0f, int(i)};
    for (size_t i = 0; i < n; ++i)
        if (!(weights[i] > 0)) m_alias[i].keep = 0, m_alias[i].other = int(heaviest);
}

bool Lights::sample(int index, const Vec3f &p, const Vec3f &n, float u1, float u2,
                    LightSample *out) const {
    const Light &l = m_lights[index];
    switch (l.type) {
        case LightDesc::Type::environment: {
            if (l.env->is_constant()) {
                const Vec3f w = sample_cosine_hemisphere(u1, u2);
                out->wi = Frame::from_z(n).to_world(w);
                out->pdf = w.z * inv_pi;
                out->Li = l.env->eval(out->wi);
            } else {
                out->Li = l.env->sample(u1, u2, &out->wi, &out->pdf);
            }
            out->distance = inf;
            out->delta = false;
            return out->pdf > 0 && !is_black(out->Li);
        }
        case LightDesc::Type::distant: {
            out->distance = inf;
            if (l.cos_max >= 1) {
                out->wi = l.to_light;
                out->Li = l.L;
                out->pdf = 1;
                out->delta = true;
                return true;
            }
            out->wi = l.frame.to_world(sample_uniform_cone(u1, u2, l.cos_max));
            out->Li = l.L;
            out->pdf = l.cone_pdf;
            out->delta = false;
            return true;
        }
        case LightDesc::Type::sphere: {
            // Sample the cone of directions the sphere subtends (PBR 3rd ed. §14.2.2).
            const Vec3f to_c = l.center - p;
            const float d2 = dot(to_c, to_c);
            if (d2 <= l.radius * l.radius) return false;  // inside: no contribution
            const float dc = std::sqrt(d2);
            const float sin2_max = l.radius * l.radius / d2;
            const float cos_max = std::sqrt(std::max(0.0f, 1 - sin2_max));
            const Frame f = Frame::from_z(to_c / dc);
            const Vec3f wi = f.to_world(sample_uniform_cone(u1, u2, cos_max));
            // Distance to the near side of the sphere along wi.
            const float b = dot(wi, to_c), disc = b * b - (d2 - l.radius * l.radius);
            out->wi = wi;
            out->distance = b - std::sqrt(std::max(0.0f, disc));
            out->Li = l.L;
            out->pdf = 1 / (2 * pi * (1 - cos_max));
            out->delta = false;
            return out->distance > 0;
        }
        case LightDesc::Type::quad: {
            const Vec3f y = l.corner + l.eu * u1 + l.ev * u2;
            const Vec3f to = y - p;
            const float dist2 = dot(to, to);
            if (dist2 <= 0) return false;
            const float dist = std::sqrt(dist2);
            const Vec3f wi = to / dist;
            const float cos_l = -dot(l.n, wi);
            if (cos_l <= 0 && !l.two_sided) return false;
            if (cos_l == 0) return false;
            out->wi = wi;
            out->distance = dist;
            out->Li = l.L;
            out->pdf = dist2 / (std::abs(cos_l) * l.area);
            out->delta = false;
            return true;
        }
    }
    return false;
}

Rgb Lights::area_radiance(int index, Vec3f o, Vec3f d, float t, float *pdf) const {
    const Light &l = m_lights[index];
    if (l.type == LightDesc::Type::sphere) {
        const Vec3f to_c = l.center - o;
        const float d2 = dot(to_c, to_c);
        if (d2 <= l.radius * l.radius) {
            *pdf = 0;
            return l.L;
        }
        const float cos_max = std::sqrt(std::max(0.0f, 1 - l.radius * l.radius / d2));
        *pdf = 1 / (2 * pi * (1 - cos_max));
        return l.L;
    }
    const float cos_l = -dot(l.n, d);
    if (cos_l <= 0 && !l.two_sided) {
        *pdf = 0;
        return {};
    }
    *pdf = t * t / (std::abs(cos_l) * l.area);
    return l.L;
}

int Lights::eval_infinite(Vec3f d, Vec3f n_prev, InfiniteHit out[], int max_out) const {
    int n = 0;
    for (int i : m_infinite) {
        if (n == max_out) break;
        const Light &l = m_lights[i];
        if (l.type == LightDesc::Type::environment) {
            const float pdf = l.env->is_constant()
                                  ? std::max(0.0f, dot(n_prev, d)) * inv_pi
                                  : l.env->pdf(d);
            out[n++] = {l.env->eval(d), pdf * m_select_pdf[i]};
        } else if (dot(d, l.to_light) >= l.cos_max) {
            out[n++] = {l.L, m_select_pdf[i] * l.cone_pdf};
        }
    }
    return n;
}

}  // namespace pelage::renderer
