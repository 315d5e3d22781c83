#include "sim/growth/growth_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/core/input_error.h"
#include "sim/mesh/closest_point.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::sim {

GrowthShape::GrowthShape(std::vector<double> ages, std::vector<std::vector<Vec3d>> keys,
                         GrowthInterpolation interpolation, double interval)
    : m_ages(std::move(ages)),
      m_keys(std::move(keys)),
      m_interpolation(interpolation),
      m_interval(interval) {}

std::vector<Vec3d> GrowthShape::at(double age) const {
    const size_t n = m_ages.size();
    if (age <= m_ages.front()) return m_keys.front();
    if (age >= m_ages.back()) return m_keys.back();
    const size_t i =
        size_t(std::upper_bound(m_ages.begin(), m_ages.end(), age) - m_ages.begin()) - 1;
    const double t0 = m_ages[i], t1 = m_ages[i + 1], h = t1 - t0;
    const double s = (age - t0) / h;
    const std::vector<Vec3d> &p0 = m_keys[i], &p1 = m_keys[i + 1];
    std::vector<Vec3d> out(p0.size());
    if (m_interpolation == GrowthInterpolation::linear) {
        for (size_t v = 0; v < out.size(); ++v) out[v] = p0[v] * (1 - s) + p1[v] * s;
        return out;
    }
    // Cubic Hermite basis; tangents scaled by the interval length h.
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const size_t a = i > 0 ? i - 1 : i, b = i + 2 < n ? i + 2 : i + 1;
    const double ta = m_ages[a], tb = m_ages[b];
    for (size_t v = 0; v < out.size(); ++v) {
        const Vec3d m0 = (p1[v] - m_keys[a][v]) / (t1 - ta);
        const Vec3d m1 = (m_keys[b][v] - p0[v]) / (tb - t0);
        out[v] = p0[v] * h00 + m0 * (h10 * h) + p1[v] * h01 + m1 * (h11 * h);
    }
    return out;
}

namespace {

// The point p as cylinder c alone grows it, its pivot moved by its ancestors.
Vec3d grow_alone(const std::vector<GrowthCylinder> &cyl,
                 const std::vector<std::array<double, 2>> &scales, int c, Vec3d p) {
    const GrowthCylinder &k = cyl[c];
    const Vec3d u = normalize(k.to - k.from);
    const double x = dot(p - k.from, u);
    const Vec3d q = p - k.from - u * x;
    const Vec3d pivot =
        k.parent >= 0 ? grow_alone(cyl, scales, k.parent, k.from) : k.from;
    return pivot + u * (scales[c][0] * x) + q * scales[c][1];
}

}  // namespace

namespace {

bool in_cylinder(const GrowthCylinder &k, Vec3d p, double *d) {
    const Vec3d axis = k.to - k.from;
    const double len = length(axis);
    const double x = dot(p - k.from, axis) / len;
    if (x < 0 || x > len) return false;
    *d = length(p - k.from - axis * (x / len)) / k.radius;
    return *d <= 1;
}

}  // namespace

size_t vertices_outside_cylinders(const std::vector<GrowthCylinder> &cylinders,
                                  const TriangleMesh &mesh) {
    size_t n = 0;
    for (const Vec3d &p : mesh.positions) {
        bool in = false;
        double d = 0;
        for (const GrowthCylinder &k : cylinders) in = in || in_cylinder(k, p, &d);
        n += in ? 0 : 1;
    }
    return n;
}

Vec3d grow_by_cylinders(const std::vector<GrowthCylinder> &cylinders,
                        const std::vector<std::array<double, 2>> &scales, Vec3d p) {
    Vec3d sum;
    double weight = 0;
    int inside = 0;
    Vec3d plain;  // the unweighted sum, for a point on every cylinder's wall
    for (size_t c = 0; c < cylinders.size(); ++c) {
        double d = 0;
        if (!in_cylinder(cylinders[c], p, &d)) continue;
        const Vec3d g = grow_alone(cylinders, scales, int(c), p);
        sum += g * (1 - d);  // thesis L1356: d_A = 1 − d_A, w_A = d_A / Σ d
        weight += 1 - d;
        plain += g;
        ++inside;
    }
    if (inside == 0) return p;
    return weight > 0 ? sum / weight : plain / double(inside);
}

Vec3d area_centroid(const TriangleMesh &mesh) {
    Vec3d sum;
    double area = 0;
    for (TriId t = 0; t < mesh.num_triangles(); ++t) {
        const double a = mesh.triangle_area(t);
        sum += (mesh.vertex(t, 0) + mesh.vertex(t, 1) + mesh.vertex(t, 2)) * (a / 3);
        area += a;
    }
    return area > 0 ? sum / area : sum;
}

std::vector<Vec3d> key_positions(const GrowthSpec &spec, size_t k,
                                 const TriangleMesh &rest) {
    const GrowthKey &key = spec.keys[k];
    std::vector<Vec3d> out(rest.num_vertices());
    switch (key.kind) {
        case GrowthKey::Kind::scale: {
            const Vec3d c = area_centroid(rest);
            for (size_t v = 0; v < out.size(); ++v)
                out[v] = c + (rest.positions[v] - c) * key.scale;
            break;
        }
        case GrowthKey::Kind::cylinders:
            for (size_t v = 0; v < out.size(); ++v)
                out[v] = grow_by_cylinders(spec.cylinders, key.cylinder_scales,
                                           rest.positions[v]);
            break;
        case GrowthKey::Kind::mesh: {
            const std::string field = key.path + ".mesh";
            TriangleMesh m;
            try {
                m = load_mesh(key.mesh);
            } catch (const InputError &e) {
                throw InputError(spec.file, 0, field,
                                 "cannot read \"" + key.mesh + "\": " + e.what());
            }
            auto mismatch = [&](const std::string &what) {
                throw InputError(
                    spec.file, 0, field,
                    "\"" + key.mesh +
                        "\" does not have the rest mesh's topology: " + what);
            };
            if (m.num_vertices() != rest.num_vertices())
                mismatch(std::to_string(m.num_vertices()) +
                         " vertices, the rest mesh has " +
                         std::to_string(rest.num_vertices()));
            if (m.num_triangles() != rest.num_triangles())
                mismatch(std::to_string(m.num_triangles()) +
                         " triangles, the rest mesh has " +
                         std::to_string(rest.num_triangles()));
            for (size_t t = 0; t < rest.num_triangles(); ++t)
                if (m.triangles[t] != rest.triangles[t])
                    mismatch("triangle " + std::to_string(t) + " has other vertices");
            out = m.positions;
            break;
        }
    }
    return out;
}

GrowthShape resolve_growth(const GrowthSpec &spec, const TriangleMesh &rest,
                           const TriangleMesh &surface) {
    const bool same = surface.num_vertices() == rest.num_vertices() &&
                      surface.triangles == rest.triangles;
    std::vector<double> ages;
    std::vector<std::vector<Vec3d>> keys;
    std::vector<MeshPoint> on_rest;
    for (size_t k = 0; k < spec.keys.size(); ++k) {
        const GrowthKey &key = spec.keys[k];
        ages.push_back(key.age);
        if (same) {
            keys.push_back(key_positions(spec, k, rest));
            continue;
        }
        if (key.kind != GrowthKey::Kind::mesh) {
            // Functions of the position: the copy's vertices directly (same centroid as
            // the rest mesh's for a scale).
            const Vec3d c = area_centroid(rest);
            std::vector<Vec3d> out(surface.num_vertices());
            for (size_t v = 0; v < out.size(); ++v)
                out[v] = key.kind == GrowthKey::Kind::scale
                             ? c + (surface.positions[v] - c) * key.scale
                             : grow_by_cylinders(spec.cylinders, key.cylinder_scales,
                                                 surface.positions[v]);
            keys.push_back(std::move(out));
            continue;
        }
        const std::vector<Vec3d> grown = key_positions(spec, k, rest);
        if (on_rest.empty())
            on_rest = closest_points(rest, surface.positions, RankBy::barycentric_blend);
        std::vector<Vec3d> out(surface.num_vertices());
        for (size_t v = 0; v < out.size(); ++v) {
            const MeshPoint &m = on_rest[v];
            Vec3d moved = surface.positions[v];
            for (int c = 0; c < 3; ++c) {
                const VertId w = rest.triangles[m.tri][c];
                moved += (grown[w] - rest.positions[w]) * m.bary[c];
            }
            out[v] = moved;
        }
        keys.push_back(std::move(out));
    }
    return GrowthShape(std::move(ages), std::move(keys), spec.interpolation,
                       spec.interval);
}

}  // namespace pelage::sim
