#include "sim/control/corner_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/mesh/closest_point.h"

namespace pelage::sim {
namespace {

// Barycentric coordinates of q, a point of triangle abc.
Vec3d barycentric_of(Vec3d q, Vec3d a, Vec3d b, Vec3d c) {
    const Vec3d e1 = b - a, e2 = c - a, r = q - a;
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double r1 = dot(r, e1), r2 = dot(r, e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(det > 0)) return {1, 0, 0};
    const double b1 = (d22 * r1 - d12 * r2) / det, b2 = (d11 * r2 - d12 * r1) / det;
    return {1 - b1 - b2, b1, b2};
}

}  // namespace

std::vector<MeshPoint> closest_source_points(const TriangleMesh &source,
                                             const TriangleMesh &target) {
    const ClosestPointGrid grid(source);
    std::vector<MeshPoint> out(3 * target.num_triangles());
    for (size_t q = 0; q < out.size(); ++q) {
        MeshPoint m = grid.closest(target.vertex(TriId(q / 3), int(q % 3)));
        if (m.tri == invalid_id) m.tri = 0;  // no finite distance: triangle 0
        // The weights from the point by least squares, not the search's own: they
        // differ by rounding, and the region values carried with them reach the
        // simulation (and so the .cells files).
        m.bary = barycentric_of(m.point, source.vertex(m.tri, 0), source.vertex(m.tri, 1),
                                source.vertex(m.tri, 2));
        out[q] = m;
    }
    return out;
}

std::vector<double> transfer_corner_values(const std::vector<MeshPoint> &map,
                                           const std::vector<double> &source_values) {
    std::vector<double> out(map.size());
    for (size_t q = 0; q < map.size(); ++q) {
        const double *v = &source_values[3 * size_t(map[q].tri)];
        const Vec3d b = map[q].bary;
        out[q] = std::clamp(b.x * v[0] + b.y * v[1] + b.z * v[2], 0.0, 1.0);
    }
    return out;
}

}  // namespace pelage::sim
