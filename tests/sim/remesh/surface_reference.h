// The simplification tests' own references, written apart from sim/remesh so that the
// tests do not check the code with itself: a count of a mesh's topology (ordered maps
// and a recursive find, where surface_topology.h sorts half-edges) and the distance to
// a mesh by brute force (Ericson's closest point on every triangle, no tree).
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "sim/mesh/closest_point.h"
#include "sim/mesh/mesh.h"

namespace pelage::test {

// V − E + F with a vertex counted once per fan of triangles around it (a vertex where
// two fans meet only at a point is two vertices of the surface, as the simplification
// splits it), and the number of edges not shared by exactly two triangles.
inline std::pair<long, long> euler_and_open_edges(const sim::TriangleMesh &m) {
    using sim::TriId, sim::VertId;
    std::map<std::pair<VertId, VertId>, std::vector<TriId>> edges;
    for (TriId t = 0; t < m.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const VertId a = m.triangles[t][c], b = m.triangles[t][(c + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back(t);
        }
    long open = 0;
    for (const auto &[e, tris] : edges) open += tris.size() != 2;
    // Fans: the corners (t, v) joined across the edges at v they share.
    std::map<std::pair<TriId, VertId>, std::pair<TriId, VertId>> parent;
    std::function<std::pair<TriId, VertId>(std::pair<TriId, VertId>)> find =
        [&](std::pair<TriId, VertId> x) {
            auto it = parent.find(x);
            if (it == parent.end() || it->second == x) return x;
            return it->second = find(it->second);
        };
    for (TriId t = 0; t < m.num_triangles(); ++t)
        for (VertId v : m.triangles[t]) parent[{t, v}] = {t, v};
    for (const auto &[e, tris] : edges)
        for (size_t k = 1; k < tris.size(); ++k)
            for (VertId v : {e.first, e.second})
                parent[find({tris[k], v})] = find({tris[0], v});
    long fans = 0;
    for (const auto &[x, p] : parent) fans += find(x) == x;
    return {fans - long(edges.size()) + long(m.num_triangles()), open};
}

// The distance from p to the nearest triangle of m.
inline double distance_to_mesh(sim::Vec3d p, const sim::TriangleMesh &m) {
    double best = 1e300;
    for (sim::TriId t = 0; t < m.num_triangles(); ++t)
        best =
            std::min(best, length(sim::closest_point_on_triangle(
                                      p, m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2)) -
                                  p));
    return best;
}

}  // namespace pelage::test
