#include "sim/crps/unfold.h"

#include <algorithm>
#include <cmath>

#include "sim/mesh/closest_point.h"

namespace pelage::sim {
namespace {

bool segments_cross(Vec2d a, Vec2d b, Vec2d c, Vec2d d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) &&
           ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// The query region (the master triangle or a point) sits inside the circle
// (region_centre, region_bound); that circle gives a cheap lower bound on the distance to
// a candidate's bounding circle, so far candidates skip the exact test.
template <typename DistanceToRegion>
void unfold(const Crps &crps, TriId master, double radius, Vec2d region_centre,
            double region_bound, DistanceToRegion &&distance,
            std::vector<UnfoldedTriangle> &out, UnfoldScratch &scratch,
            UnfoldPaths paths) {
    out.clear();
    scratch.prepare(crps.num_triangles());
    scratch.begin();
    const Topology &topo = crps.topology();

    scratch.visit(master);
    out.push_back({master, 0, RigidMap2{}, distance(crps.frame(master).v.data())});
    for (size_t head = 0; head < out.size(); ++head) {
        const UnfoldedTriangle parent = out[head];
        const auto nbrs = topo.neighbours(parent.tri);
        const auto maps = crps.to_master(parent.tri);
        const size_t n =
            paths == UnfoldPaths::edges_only ? topo.num_primary[parent.tri] : nbrs.size();
        for (size_t k = 0; k < n; ++k) {
            const TriId j = nbrs[k];
            // Cheap rejection first: already accepted in this unfolding.
            if (!scratch.visit(j)) continue;
            const RigidMap2 F = compose(parent.to_master, maps[k]);
            const CrpsFrame &fj = crps.frame(j);
            // Bounds before the exact test. F maps j's centroid (its local origin) to
            // (ax, ay); both the region's centre and j's centroid lie inside their
            // shapes, so the centres' distance bounds the shapes' distance from above,
            // and minus both bounding radii from below.
            const double centre_gap = length(Vec2d{F.ax, F.ay} - region_centre);
            const double lower = centre_gap - region_bound - fj.bound_radius;
            if (lower > radius) {
                scratch.unvisit(j);  // another path may bring it closer
                continue;
            }
            if (centre_gap <= radius) {
                out.push_back({j, parent.depth + 1, F, std::max(lower, 0.0)});
                continue;
            }
            const Vec2d mapped[3] = {F.apply(fj.v[0]), F.apply(fj.v[1]),
                                     F.apply(fj.v[2])};
            const double d = distance(mapped);
            if (d <= radius) {
                out.push_back({j, parent.depth + 1, F, d});
            } else {
                scratch.unvisit(j);  // another path may bring it closer
            }
        }
    }
}

}  // namespace

void UnfoldScratch::prepare(size_t n) {
    if (m_stamp.size() != n) {
        m_stamp.assign(n, 0);
        m_generation = 0;
    }
}

void UnfoldScratch::begin() {
    if (++m_generation == 0) {  // wrapped: clear once every 2^32 unfoldings
        std::fill(m_stamp.begin(), m_stamp.end(), 0);
        m_generation = 1;
    }
}

// Disjoint convex polygons are closest at a vertex of one of them; overlapping ones have
// a vertex inside the other or crossing edges.
double triangle_triangle_distance(const Vec2d a[3], const Vec2d b[3]) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (segments_cross(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return 0.0;
    double d = 1e300;
    for (int i = 0; i < 3; ++i) {
        d = std::min(d, point_triangle_distance(a[i], b));
        d = std::min(d, point_triangle_distance(b[i], a));
    }
    return d;
}

void unfold_around_triangle(const Crps &crps, TriId master, double radius,
                            std::vector<UnfoldedTriangle> &out, UnfoldScratch &scratch,
                            UnfoldPaths paths) {
    const Vec2d *m = crps.frame(master).v.data();
    unfold(
        crps, master, radius, Vec2d{0, 0}, crps.frame(master).bound_radius,
        [m](const Vec2d *mapped) { return triangle_triangle_distance(m, mapped); }, out,
        scratch, paths);
}

void unfold_around_point(const Crps &crps, TriId master, Vec2d q, double radius,
                         std::vector<UnfoldedTriangle> &out, UnfoldScratch &scratch,
                         UnfoldPaths paths) {
    unfold(
        crps, master, radius, q, 0.0,
        [q](const Vec2d *mapped) { return point_triangle_distance(q, mapped); }, out,
        scratch, paths);
}

}  // namespace pelage::sim
