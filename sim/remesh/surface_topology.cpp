#include "sim/remesh/surface_topology.h"

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "sim/core/disjoint_sets.h"

namespace pelage::sim {

TopologyDetail analyse_topology(const TriangleMesh &mesh) {
    TopologyDetail detail;
    SurfaceTopology &top = detail.top;
    const size_t nf = mesh.num_triangles(), nv = mesh.num_vertices();
    // Every edge once per face, keyed by its ends (low, high), then its face corner.
    struct HalfEdge {
        VertId lo, hi;
        uint32_t corner;  // 3·face + corner of its first end
        bool forward;     // lo → hi in the face's order
    };
    std::vector<HalfEdge> edges;
    edges.reserve(3 * nf);
    for (size_t f = 0; f < nf; ++f)
        for (int c = 0; c < 3; ++c) {
            const VertId a = mesh.triangles[f][c], b = mesh.triangles[f][(c + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), uint32_t(3 * f + c), a < b});
        }
    std::sort(edges.begin(), edges.end(), [](const HalfEdge &x, const HalfEdge &y) {
        return std::tie(x.lo, x.hi, x.corner) < std::tie(y.lo, y.hi, y.corner);
    });
    // Fans: the corners of a vertex joined across the edges at it that two faces share.
    DisjointSets corners(3 * nf), faces(nf), boundary(nv);
    const auto corner_of = [&](uint32_t face, VertId v) {
        const auto &t = mesh.triangles[face];
        return uint32_t(3 * face + (t[0] == v ? 0 : t[1] == v ? 1 : 2));
    };
    top.edge_manifold = true;
    long num_edges = 0;
    std::vector<char> &on_boundary = detail.on_boundary;
    on_boundary.assign(nv, 0);
    for (size_t i = 0; i < edges.size();) {
        size_t j = i + 1;
        while (j < edges.size() && edges[j].lo == edges[i].lo &&
               edges[j].hi == edges[i].hi)
            ++j;
        ++num_edges;
        const VertId a = edges[i].lo, b = edges[i].hi;
        if (j - i == 1) {
            boundary.unite(a, b);
            on_boundary[a] = on_boundary[b] = 1;
        } else if (j - i == 2 && edges[i].forward != edges[i + 1].forward) {
            const uint32_t f = edges[i].corner / 3, g = edges[i + 1].corner / 3;
            faces.unite(f, g);
            corners.unite(corner_of(f, a), corner_of(g, a));
            corners.unite(corner_of(f, b), corner_of(g, b));
        } else {
            top.edge_manifold = false;  // three faces on an edge, or two facing one way
        }
        i = j;
    }
    std::vector<uint32_t> &fans = detail.fans;
    fans.assign(nv, 0);
    long num_fans = 0;
    for (uint32_t k = 0; k < 3 * nf; ++k)
        if (corners.find(k) == k) {
            ++fans[mesh.triangles[k / 3][k % 3]];
            ++num_fans;
        }
    for (VertId v = 0; v < nv; ++v) {
        top.pinched += fans[v] > 1;
        top.boundary_loops += on_boundary[v] && boundary.find(v) == v;
    }
    for (uint32_t f = 0; f < nf; ++f) top.components += faces.find(f) == f;
    top.euler = num_fans - num_edges + long(nf);
    return detail;
}

SurfaceTopology surface_topology(const TriangleMesh &mesh) {
    return analyse_topology(mesh).top;
}

}  // namespace pelage::sim
