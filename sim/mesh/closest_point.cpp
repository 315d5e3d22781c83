#include "sim/mesh/closest_point.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {
namespace {

double point_segment_distance_sq(Vec2d p, Vec2d a, Vec2d b) {
    const Vec2d ab = b - a;
    const double len2 = length_squared(ab);
    const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length_squared(p - (a + ab * t));
}

bool inside_triangle(Vec2d p, const Vec2d t[3]) {
    // Orientation-agnostic: p is inside when it is on the same side of all three edges.
    const double d0 = cross(t[1] - t[0], p - t[0]);
    const double d1 = cross(t[2] - t[1], p - t[1]);
    const double d2 = cross(t[0] - t[2], p - t[2]);
    const bool has_neg = d0 < 0 || d1 < 0 || d2<0, has_pos = d0> 0 || d1 > 0 || d2 > 0;
    return !(has_neg && has_pos);
}

}  // namespace

double point_triangle_distance(Vec2d p, const Vec2d t[3]) {
    if (inside_triangle(p, t)) return 0.0;
    return std::sqrt(std::min({point_segment_distance_sq(p, t[0], t[1]),
                               point_segment_distance_sq(p, t[1], t[2]),
                               point_segment_distance_sq(p, t[2], t[0])}));
}

MeshPoint closest_surface_point(const TriangleMesh &mesh, Vec3d p) {
    MeshPoint best;
    for (TriId t = 0; t < mesh.num_triangles(); ++t) {
        const TrianglePoint q = closest_on_triangle(p, mesh.vertex(t, 0),
                                                    mesh.vertex(t, 1), mesh.vertex(t, 2));
        const double d = length(q.point - p);
        if (d < best.distance) best = {t, q.point, q.bary, d};
    }
    return best;
}

ClosestPointGrid::ClosestPointGrid(const TriangleMesh &m) : m_mesh(&m) {
    const Bounds3 b = m.bounds();
    m_lo = b.lo;
    double edges = 0;
    for (TriId t = 0; t < m.num_triangles(); ++t)
        edges += length(m.vertex(t, 1) - m.vertex(t, 0));
    m_cell = std::max(edges / std::max<size_t>(m.num_triangles(), 1), 1e-12);
    for (int k = 0; k < 3; ++k)
        m_n[k] = std::clamp(int((b.hi[k] - b.lo[k]) / m_cell) + 1, 1, 1024);
    m_cell = std::max({(b.hi.x - b.lo.x) / m_n[0], (b.hi.y - b.lo.y) / m_n[1],
                       (b.hi.z - b.lo.z) / m_n[2], m_cell * 1e-3});
    for (TriId t = 0; t < m.num_triangles(); ++t) {
        Vec3d lo = m.vertex(t, 0), hi = lo;
        for (int c = 1; c < 3; ++c) {
            const Vec3d v = m.vertex(t, c);
            lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
            hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
        }
        const auto a = index_of(lo), z = index_of(hi);
        for (int i = a[0]; i <= z[0]; ++i)
            for (int j = a[1]; j <= z[1]; ++j)
                for (int k = a[2]; k <= z[2]; ++k) m_cells[key(i, j, k)].push_back(t);
    }
}

std::array<int, 3> ClosestPointGrid::index_of(Vec3d p) const {
    return {int(std::floor((p.x - m_lo.x) / m_cell)),
            int(std::floor((p.y - m_lo.y) / m_cell)),
            int(std::floor((p.z - m_lo.z) / m_cell))};
}

uint64_t ClosestPointGrid::key(int i, int j, int k) {
    return (uint64_t(uint32_t(i + (1 << 20))) << 42) ^
           (uint64_t(uint32_t(j + (1 << 20))) << 21) ^ uint64_t(uint32_t(k + (1 << 20)));
}

// Visits the triangles of the shells of cells around p's, outwards, until every
// triangle left lies farther than `reach` (which `visit` may lower as it goes): the
// occupied cells have indices 0 .. m_n[k] along axis k, and every triangle outside the
// shells searched is at least (r - 1) cells away.
template <typename Visit>
void ClosestPointGrid::search(Vec3d p, const double &reach, Visit &&visit) const {
    const auto c = index_of(p);
    int far = 0;
    for (int k = 0; k < 3; ++k)
        far = std::max({far, std::abs(c[k]), std::abs(m_n[k] - c[k])});
    for (int r = 0; r <= far + 1; ++r) {
        if (r > 0 && reach < (r - 1) * m_cell) break;
        for (int i = c[0] - r; i <= c[0] + r; ++i)
            for (int j = c[1] - r; j <= c[1] + r; ++j)
                for (int k = c[2] - r; k <= c[2] + r; ++k) {
                    if (std::max({std::abs(i - c[0]), std::abs(j - c[1]),
                                  std::abs(k - c[2])}) != r)
                        continue;  // the shell only
                    const auto it = m_cells.find(key(i, j, k));
                    if (it == m_cells.end()) continue;
                    for (TriId t : it->second) visit(t);
                }
    }
}

MeshPoint ClosestPointGrid::closest(Vec3d p, RankBy rank) const {
    MeshPoint best;
    best.tri = invalid_id;
    double best_key = std::numeric_limits<double>::infinity();
    search(p, best.distance, [&](TriId t) {
        const Vec3d a = m_mesh->vertex(t, 0), b = m_mesh->vertex(t, 1),
                    c = m_mesh->vertex(t, 2);
        const TrianglePoint q = closest_on_triangle(p, a, b, c);
        if (rank == RankBy::point) {
            const double d = length(q.point - p);
            if (d < best_key || (d == best_key && t < best.tri)) {
                best_key = d;
                best = {t, q.point, q.bary, d};
            }
        } else {
            const Vec3d x = a * q.bary.x + b * q.bary.y + c * q.bary.z;
            const double d2 = length_squared(x - p);
            if (d2 < best_key || (d2 == best_key && t < best.tri)) {
                best_key = d2;
                best = {t, x, q.bary, std::sqrt(d2)};
            }
        }
    });
    return best;
}

MeshPoint ClosestPointGrid::closest_facing(Vec3d p, Vec3d normal, double tie) const {
    MeshPoint best;
    best.tri = invalid_id;
    best.point = p;
    double best_facing = -1, reach = best.distance + tie;
    search(p, reach, [&](TriId t) {
        const TrianglePoint q = closest_on_triangle(
            p, m_mesh->vertex(t, 0), m_mesh->vertex(t, 1), m_mesh->vertex(t, 2));
        const double d = length(q.point - p);
        const double facing =
            std::abs(dot(normalize(m_mesh->face_normal_unnormalized(t)), normal));
        const bool closer = d < best.distance - tie;
        const bool tied = !closer && d <= best.distance + tie;
        if (closer ||
            (tied && (facing > best_facing || (facing == best_facing && t < best.tri)))) {
            best = {t, q.point, q.bary, d};
            best_facing = facing;
            reach = best.distance + tie;
        }
    });
    return best;
}

std::vector<MeshPoint> closest_points(const TriangleMesh &mesh,
                                      const std::vector<Vec3d> &points, RankBy rank) {
    std::vector<MeshPoint> out(points.size());
    if (mesh.num_triangles() == 0) return out;
    const ClosestPointGrid grid(mesh);
    for (size_t i = 0; i < points.size(); ++i) {
        out[i] = grid.closest(points[i], rank);
        // No triangle at a finite distance (a non-finite point): triangle 0 with zero
        // weights, so a caller indexing by the triangle stays in range.
        if (out[i].tri == invalid_id) out[i] = MeshPoint{};
    }
    return out;
}

}  // namespace pelage::sim
