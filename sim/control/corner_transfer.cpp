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

std::vector<ClosestSource> closest_source_points(const TriangleMesh &source,
                                                 const TriangleMesh &target) {
    // Grid cells about twice the source's mean edge, at most 256 a side.
    const Bounds3 box = source.bounds();
    double edges = 0;
    for (TriId t = 0; t < source.num_triangles(); ++t)
        edges += length(source.vertex(t, 1) - source.vertex(t, 0));
    const double mean_edge = edges / double(std::max<size_t>(source.num_triangles(), 1));
    const Vec3d size = box.hi - box.lo;
    double cell = std::max({2 * mean_edge, size.x / 256, size.y / 256, size.z / 256,
                            1e-12 * (box.diagonal() + 1e-300)});
    int n[3];
    for (int k = 0; k < 3; ++k) n[k] = std::max(1, int(std::ceil(size[k] / cell)));
    auto index = [&](int i, int j, int k) { return (size_t(k) * n[1] + j) * n[0] + i; };
    auto coord = [&](double x, int k) {
        return std::clamp(int(std::floor((x - box.lo[k]) / cell)), 0, n[k] - 1);
    };
    std::vector<std::vector<TriId>> grid(size_t(n[0]) * n[1] * n[2]);
    for (TriId t = 0; t < source.num_triangles(); ++t) {
        int lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            const double a = source.vertex(t, 0)[k], b = source.vertex(t, 1)[k],
                         c = source.vertex(t, 2)[k];
            lo[k] = coord(std::min({a, b, c}), k);
            hi[k] = coord(std::max({a, b, c}), k);
        }
        for (int k = lo[2]; k <= hi[2]; ++k)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int i = lo[0]; i <= hi[0]; ++i) grid[index(i, j, k)].push_back(t);
    }
    std::vector<ClosestSource> out(3 * target.num_triangles());
    for (size_t q = 0; q < out.size(); ++q) {
        const Vec3d p = target.vertex(TriId(q / 3), int(q % 3));
        const int c[3] = {coord(p.x, 0), coord(p.y, 1), coord(p.z, 2)};
        double best = std::numeric_limits<double>::infinity();
        TriId best_tri = 0;
        Vec3d best_point;
        const int max_ring = std::max({n[0], n[1], n[2]});
        for (int ring = 0; ring <= max_ring; ++ring) {
            // The cells at Chebyshev distance `ring` from p's cell.
            for (int k = c[2] - ring; k <= c[2] + ring; ++k)
                for (int j = c[1] - ring; j <= c[1] + ring; ++j)
                    for (int i = c[0] - ring; i <= c[0] + ring; ++i) {
                        if (std::max({std::abs(i - c[0]), std::abs(j - c[1]),
                                      std::abs(k - c[2])}) != ring)
                            continue;
                        if (i < 0 || j < 0 || k < 0 || i >= n[0] || j >= n[1] ||
                            k >= n[2])
                            continue;
                        for (TriId t : grid[index(i, j, k)]) {
                            const Vec3d x = closest_point_on_triangle(
                                p, source.vertex(t, 0), source.vertex(t, 1),
                                source.vertex(t, 2));
                            const double d = length(x - p);
                            if (d < best || (d == best && t < best_tri)) {
                                best = d;
                                best_tri = t;
                                best_point = x;
                            }
                        }
                    }
            // Every triangle not yet seen lies in cells beyond this ring, farther than
            // ring·cell from p.
            if (best <= ring * cell) break;
        }
        out[q] = {best_tri,
                  barycentric_of(best_point, source.vertex(best_tri, 0),
                                 source.vertex(best_tri, 1), source.vertex(best_tri, 2))};
    }
    return out;
}

std::vector<double> transfer_corner_values(const std::vector<ClosestSource> &map,
                                           const std::vector<double> &source_values) {
    std::vector<double> out(map.size());
    for (size_t q = 0; q < map.size(); ++q) {
        const double *v = &source_values[3 * size_t(map[q].tri)];
        const Vec3d b = map[q].b;
        out[q] = std::clamp(b.x * v[0] + b.y * v[1] + b.z * v[2], 0.0, 1.0);
    }
    return out;
}

}  // namespace pelage::sim
