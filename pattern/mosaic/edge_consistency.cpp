#include "pattern/mosaic/edge_consistency.h"

#include <cmath>

namespace pelage::pattern::mosaic {

EdgeConsistency measure_edge_consistency(const sim::TriangleMesh &mesh,
                                         const sim::Crps &crps,
                                         const ClosestCellIndex &index, int per_edge) {
    EdgeConsistency r;
    const sim::Topology &topo = crps.topology();
    auto to_f = [](sim::Vec2d p) { return Vec2f{float(p.x), float(p.y)}; };
    for (sim::EdgeId e = 0; e < topo.num_edges(); ++e) {
        if (!topo.is_manifold(e)) continue;
        const auto f = topo.faces_of_edge(e);
        const sim::Vec3d a = mesh.positions[topo.edge_vertices[e][0]];
        const sim::Vec3d b = mesh.positions[topo.edge_vertices[e][1]];
        for (int k = 0; k < per_edge; ++k) {
            const sim::Vec3d p = a + (b - a) * ((k + 0.5) / per_edge);
            const Vec2f qa = to_f(crps.to_2d(f[0], p)), qb = to_f(crps.to_2d(f[1], p));
            const ClosestCell ca = index.find(f[0], qa), cb = index.find(f[1], qb);
            ++r.samples;
            if (ca.index == cb.index) continue;
            ++r.cracks;
            const float a1 = index.distance_to_cell(f[0], qa, ca.index);
            const float a2 = index.distance_to_cell(f[0], qa, cb.index);
            const float b1 = index.distance_to_cell(f[1], qb, ca.index);
            const float b2 = index.distance_to_cell(f[1], qb, cb.index);
            // Float rounding of maps and positions: 1e-5 of the distance.
            const float tol = 1e-5f * (a1 + b2) + 1e-7f;
            const bool same_unfolding =
                std::abs(a1 - b1) <= tol && std::abs(a2 - b2) <= tol;
            if (same_unfolding && std::abs(a1 - a2) > 2 * tol) {
                ++r.inconsistent;
                --r.cracks;
            }
        }
    }
    return r;
}

}  // namespace pelage::pattern::mosaic
