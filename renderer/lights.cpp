#include "renderer/lights.h"

#include <cmath>
#include <limits>

#include "renderer/sampling.h"

namespace pelage::renderer {

namespace {
constexpr float inf = std::numeric_limits<float>::infinity();
}

Lights::Lights(const std::vector<LightDesc> &descs) {
    for (const LightDesc &d : descs) {
        Light l;
        l.type = d.type;
        l.L = d.color * d.intensity;
        switch (d.type) {
            case LightDesc::Type::environment:
                l.env = d.image.empty() ? std::make_shared<EnvironmentLight>(l.L)
                                        : std::make_shared<EnvironmentLight>(
                                              d.image, d.intensity, d.rotation_deg);
                m_infinite.push_back(int(m_lights.size()));
                break;
            case LightDesc::Type::distant: {
                l.to_light = -normalize(d.direction);
                l.frame = Frame::from_z(l.to_light);
                const float half = 0.5f * d.angle_deg * pi / 180;
                l.cos_max = std::cos(half);
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
                m_area.push_back(int(m_lights.size()));
                break;
            case LightDesc::Type::quad: {
                l.corner = d.corner;
                l.eu = d.edge_u;
                l.ev = d.edge_v;
                const Vec3f c = cross(d.edge_u, d.edge_v);
                l.area = length(c);
                l.n = c / l.area;
                l.two_sided = d.two_sided;
                m_area.push_back(int(m_lights.size()));
                break;
            }
        }
        m_lights.push_back(std::move(l));
    }
}

bool Lights::sample(int index, Vec3f p, Vec3f n, float u1, float u2,
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
            out->pdf = 1 / (2 * pi * (1 - l.cos_max));
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

AreaLightHit Lights::intersect(Vec3f o, Vec3f d, float t_max) const {
    AreaLightHit best;
    best.t = t_max;
    for (int i : m_area) {
        const Light &l = m_lights[i];
        float t = -1;
        if (l.type == LightDesc::Type::sphere) {
            const Vec3f oc = o - l.center;
            const float b = dot(oc, d), c = dot(oc, oc) - l.radius * l.radius,
                        disc = b * b - c;
            if (disc < 0) continue;
            const float sq = std::sqrt(disc);
            t = -b - sq;
            if (t <= 0) t = -b + sq;
        } else {
            const float denom = dot(d, l.n);
            if (denom == 0) continue;
            t = dot(l.corner - o, l.n) / denom;
            if (t <= 0) continue;
            const Vec3f q = o + d * t - l.corner;
            // Coordinates along the (possibly non-orthogonal) edges.
            const float uu = dot(l.eu, l.eu), uv = dot(l.eu, l.ev), vv = dot(l.ev, l.ev);
            const float qu = dot(q, l.eu), qv = dot(q, l.ev), det = uu * vv - uv * uv;
            const float a = (qu * vv - qv * uv) / det, b = (qv * uu - qu * uv) / det;
            if (a < 0 || a > 1 || b < 0 || b > 1) continue;
        }
        if (t > 0 && t < best.t) {
            best.t = t;
            best.light = i;
        }
    }
    return best;
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
            out[n++] = {l.env->eval(d), pdf};
        } else if (dot(d, l.to_light) >= l.cos_max) {
            out[n++] = {l.L, 1 / (2 * pi * (1 - l.cos_max))};
        }
    }
    return n;
}

}  // namespace pelage::renderer
