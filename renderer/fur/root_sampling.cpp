#include "renderer/fur/root_sampling.h"

#include <algorithm>
#include <cmath>

#include "renderer/fur/fur_hash.h"

namespace pelage::renderer {

namespace {

Vec3f vertex(const SkinMesh &m, uint32_t v) {
    return {m.positions[3 * size_t(v)], m.positions[3 * size_t(v) + 1],
            m.positions[3 * size_t(v) + 2]};
}

}  // namespace

RootSampler::RootSampler(const SkinMesh &mesh) : m_mesh(mesh) {
    m_cdf.resize(mesh.num_triangles);
    SkinMesh areas = mesh;
    if (mesh.rest_positions) areas.positions = mesh.rest_positions;
    double sum = 0;
    for (uint32_t t = 0; t < mesh.num_triangles; ++t) {
        const uint32_t *tri = &mesh.triangles[3 * size_t(t)];
        const Vec3f p0 = vertex(areas, tri[0]);
        sum +=
            0.5 *
            double(length(cross(vertex(areas, tri[1]) - p0, vertex(areas, tri[2]) - p0)));
        m_cdf[t] = sum;
    }
}

SurfacePoint RootSampler::sample(uint64_t seed, uint64_t i) const {
    // Pick a triangle with probability area / total (binary search of the CDF)
    const double u0 = uniform(seed, Stream::roots, i, 0) * area();
    const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u0);
    const uint32_t t = uint32_t(std::min<size_t>(it - m_cdf.begin(), m_cdf.size() - 1));
    // Uniform barycentrics: b0 = 1 − √u1, b1 = u2·√u1 (Turk 1990, Graphics Gems
    // "Generating random points in triangles"), b2 = 1 − b0 − b1.
    const double su = std::sqrt(uniform(seed, Stream::roots, i, 1));
    const double u2 = uniform(seed, Stream::roots, i, 2);
    const double b0 = 1 - su, b1 = u2 * su;
    return {t, float(b1), float(std::max(0.0, 1 - b0 - b1))};
}

void RootSampler::point_normal(const SurfacePoint &s, Vec3f *p, Vec3f *n) const {
    const uint32_t *tri = &m_mesh.triangles[3 * size_t(s.triangle)];
    const float b0 = 1 - s.b1 - s.b2;
    const Vec3f p0 = vertex(m_mesh, tri[0]), p1 = vertex(m_mesh, tri[1]),
                p2 = vertex(m_mesh, tri[2]);
    *p = p0 * b0 + p1 * s.b1 + p2 * s.b2;
    Vec3f face = cross(p1 - p0, p2 - p0);
    face = divide_exactly(face, std::max(length(face), 1e-30f));
    Vec3f normal = face;
    if (m_mesh.corner_normals) {
        const float *N = &m_mesh.corner_normals[9 * size_t(s.triangle)];
        const Vec3f ns = Vec3f{N[0], N[1], N[2]} * b0 + Vec3f{N[3], N[4], N[5]} * s.b1 +
                         Vec3f{N[6], N[7], N[8]} * s.b2;
        const float len = length(ns);
        if (len > 0) normal = divide_exactly(ns, len);
    }
    *n = normal;
}

uint64_t candidate_count(double expected, uint64_t seed) {
    const double whole = std::floor(expected);
    return uint64_t(whole) +
           (uniform(seed, Stream::thinning, ~0ull, 0) < expected - whole);
}

}  // namespace pelage::renderer
