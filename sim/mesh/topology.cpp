#include "sim/mesh/topology.h"

#include <algorithm>
#include <deque>
#include <tuple>

namespace pelage::sim {
namespace {

// True when triangle `tri` walks its edge from a to b (rather than b to a).
bool walks(const std::array<VertId, 3> &tri, VertId a, VertId b) {
    for (int k = 0; k < 3; ++k)
        if (tri[k] == a && tri[(k + 1) % 3] == b) return true;
    return false;
}

void build_edges(const TriangleMesh &mesh, Topology &topo) {
    const size_t nt = mesh.num_triangles();
    struct HalfEdge {
        VertId lo, hi;
        TriId t;
        uint8_t k;
    };
    // Counting sort by the lower vertex, then a tiny sort inside each vertex's bucket:
    // linear in the mesh size (a global sort would be the build's only n log n step).
    const size_t nv = mesh.num_vertices();
    std::vector<uint32_t> bucket(nv + 1, 0);
    for (TriId t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            ++bucket[std::min(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]) + 1];
    for (size_t v = 0; v < nv; ++v) bucket[v + 1] += bucket[v];
    std::vector<HalfEdge> half(3 * nt);
    std::vector<uint32_t> fill(bucket.begin(), bucket.end() - 1);
    for (TriId t = 0; t < nt; ++t)
        for (uint8_t k = 0; k < 3; ++k) {
            const VertId a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            half[fill[std::min(a, b)]++] = {std::min(a, b), std::max(a, b), t, k};
        }
    for (size_t v = 0; v < nv; ++v)
        std::sort(half.begin() + bucket[v], half.begin() + bucket[v + 1],
                  [](const HalfEdge &x, const HalfEdge &y) {
                      return std::tie(x.hi, x.t, x.k) < std::tie(y.hi, y.t, y.k);
                  });
    topo.tri_edges.assign(nt, {invalid_id, invalid_id, invalid_id});
    topo.edge_face_row.push_back(0);
    for (size_t i = 0; i < half.size();) {
        size_t j = i;
        const EdgeId e = static_cast<EdgeId>(topo.edge_vertices.size());
        topo.edge_vertices.push_back({half[i].lo, half[i].hi});
        for (; j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi;
             ++j) {
            topo.tri_edges[half[j].t][half[j].k] = e;
            // A duplicated face lists the same triangle once per copy; keep each face
            // once.
            if (topo.edge_faces.size() == topo.edge_face_row.back() ||
                topo.edge_faces.back() != half[j].t)
                topo.edge_faces.push_back(half[j].t);
        }
        topo.edge_face_row.push_back(static_cast<uint32_t>(topo.edge_faces.size()));
        const size_t n = topo.edge_face_row[e + 1] - topo.edge_face_row[e];
        topo.boundary_edges += n == 1;
        topo.nonmanifold_edges += n > 2;
        i = j;
    }
}

void build_fans(const TriangleMesh &mesh, Topology &topo) {
    const size_t nv = mesh.num_vertices(), nt = mesh.num_triangles();
    // Counting sort of (vertex, triangle) pairs: each fan comes out in triangle-id order.
    topo.fan_row.assign(nv + 1, 0);
    for (const auto &tri : mesh.triangles)
        for (VertId v : tri) ++topo.fan_row[v + 1];
    for (size_t v = 0; v < nv; ++v) topo.fan_row[v + 1] += topo.fan_row[v];
    topo.fan.resize(topo.fan_row[nv]);
    std::vector<uint32_t> fill(topo.fan_row.begin(), topo.fan_row.end() - 1);
    for (TriId t = 0; t < nt; ++t)
        for (VertId v : mesh.triangles[t]) topo.fan[fill[v]++] = t;

    // Order each fan by walking from face to face across the edges incident to v.
    topo.fan_ordered.assign(nv, 0);
    std::vector<TriId> ordered;
    for (VertId v = 0; v < nv; ++v) {
        const std::span<TriId> f(topo.fan.data() + topo.fan_row[v],
                                 topo.fan_row[v + 1] - topo.fan_row[v]);
        if (f.empty()) continue;
        // The two edges of face t incident to v.
        auto incident_edges = [&](TriId t) {
            std::array<EdgeId, 2> es{};
            int n = 0;
            for (int k = 0; k < 3; ++k) {
                const EdgeId e = topo.tri_edges[t][k];
                if (topo.edge_vertices[e][0] == v || topo.edge_vertices[e][1] == v)
                    es[n++ & 1] = e;
            }
            return es;
        };
        // Start on a boundary edge when there is one, so an open fan is walked end to
        // end.
        TriId start = f[0];
        EdgeId came_from = invalid_id;
        bool manifold = true;
        for (TriId t : f)
            for (EdgeId e : incident_edges(t)) {
                manifold &= topo.edge_face_row[e + 1] - topo.edge_face_row[e] <= 2;
                if (came_from == invalid_id && topo.is_boundary(e)) {
                    start = t;
                    came_from = e;
                }
            }
        ordered.clear();
        if (manifold) {
            TriId t = start;
            for (size_t step = 0; step < f.size() && t != invalid_id; ++step) {
                ordered.push_back(t);
                const auto es = incident_edges(t);
                const EdgeId out = es[0] == came_from ? es[1] : es[0];
                TriId next = invalid_id;
                if (topo.is_manifold(out))
                    for (TriId u : topo.faces_of_edge(out))
                        if (u != t) next = u;
                came_from = out;
                t = next == start ? invalid_id : next;
            }
        }
        std::vector<TriId> check(ordered);
        std::sort(check.begin(), check.end());
        if (manifold && check.size() == f.size() &&
            std::equal(check.begin(), check.end(), f.begin())) {
            std::copy(ordered.begin(), ordered.end(), f.begin());
            topo.fan_ordered[v] = 1;
        } else {
            ++topo.nonmanifold_vertices;
        }
    }
}

void build_neighbours(const TriangleMesh &mesh, Topology &topo) {
    const size_t nt = mesh.num_triangles();
    topo.nbr_row.assign(1, 0);
    topo.num_primary.assign(nt, 0);
    std::vector<TriId> primary, secondary;
    for (TriId t = 0; t < nt; ++t) {
        primary.clear();
        secondary.clear();
        for (EdgeId e : topo.tri_edges[t])
            for (TriId u : topo.faces_of_edge(e))
                if (u != t) primary.push_back(u);
        std::sort(primary.begin(), primary.end());
        primary.erase(std::unique(primary.begin(), primary.end()), primary.end());
        for (VertId v : mesh.triangles[t])
            for (TriId u : topo.fan_of(v))
                if (u != t && !std::binary_search(primary.begin(), primary.end(), u))
                    secondary.push_back(u);
        std::sort(secondary.begin(), secondary.end());
        secondary.erase(std::unique(secondary.begin(), secondary.end()), secondary.end());
        // A triangle with more than 255 edge neighbours only arises from pathological
        // non-manifold edges; the rest are still reachable as secondary neighbours.
        const size_t np = std::min<size_t>(primary.size(), 255);
        topo.num_primary[t] = static_cast<uint8_t>(np);
        topo.nbr.insert(topo.nbr.end(), primary.begin(), primary.begin() + np);
        topo.nbr.insert(topo.nbr.end(), primary.begin() + np, primary.end());
        topo.nbr.insert(topo.nbr.end(), secondary.begin(), secondary.end());
        topo.nbr_row.push_back(static_cast<uint32_t>(topo.nbr.size()));
    }
}

// Breadth-first over manifold edges: a neighbour that walks the shared edge in the same
// direction as its (already oriented) parent is flipped. Each component then keeps the
// majority winding, so a mesh with a few inverted faces keeps its outward normals.
void orient(const TriangleMesh &mesh, Topology &topo) {
    const size_t nt = mesh.num_triangles();
    topo.flipped.assign(nt, 0);
    topo.component.assign(nt, invalid_id);
    std::deque<TriId> queue;
    std::vector<TriId> members;
    for (TriId seed = 0; seed < nt; ++seed) {
        if (topo.component[seed] != invalid_id) continue;
        const uint32_t c = static_cast<uint32_t>(topo.num_components++);
        topo.component[seed] = c;
        queue.push_back(seed);
        members.clear();
        while (!queue.empty()) {
            const TriId t = queue.front();
            queue.pop_front();
            members.push_back(t);
            for (int k = 0; k < 3; ++k) {
                const EdgeId e = topo.tri_edges[t][k];
                if (!topo.is_manifold(e)) continue;
                const TriId u = topo.across(t, k);
                if (topo.component[u] != invalid_id) continue;
                const VertId a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
                // t walks a->b in its own winding; after its flip, the oriented
                // direction.
                const bool t_ab = !topo.flipped[t];
                const bool u_ab = walks(mesh.triangles[u], a, b);
                topo.flipped[u] = (u_ab == t_ab) ? 1 : 0;
                topo.component[u] = c;
                queue.push_back(u);
            }
        }
        size_t n_flipped = 0;
        for (TriId t : members) n_flipped += topo.flipped[t];
        if (2 * n_flipped > members.size())
            for (TriId t : members) topo.flipped[t] ^= 1;
    }
    for (TriId t : topo.flipped) topo.faces_reoriented += t;
    for (EdgeId e = 0; e < topo.num_edges(); ++e) {
        if (!topo.is_manifold(e)) continue;
        const auto f = topo.faces_of_edge(e);
        const VertId a = topo.edge_vertices[e][0], b = topo.edge_vertices[e][1];
        const bool d0 = walks(mesh.triangles[f[0]], a, b) != bool(topo.flipped[f[0]]);
        const bool d1 = walks(mesh.triangles[f[1]], a, b) != bool(topo.flipped[f[1]]);
        topo.nonorientable_edges += d0 == d1;
    }
}

}  // namespace

TriId Topology::across(TriId t, int k) const {
    const EdgeId e = tri_edges[t][k];
    if (!is_manifold(e)) return invalid_id;
    const auto f = faces_of_edge(e);
    return f[0] == t ? f[1] : f[0];
}

Topology build_topology(const TriangleMesh &mesh) {
    Topology topo;
    build_edges(mesh, topo);
    build_fans(mesh, topo);
    build_neighbours(mesh, topo);
    orient(mesh, topo);
    return topo;
}

double mean_edge_length(const TriangleMesh &mesh, const Topology &topo) {
    double sum = 0;
    for (const auto &e : topo.edge_vertices)
        sum += length(mesh.positions[e[1]] - mesh.positions[e[0]]);
    return topo.num_edges() ? sum / topo.num_edges() : 0.0;
}

}  // namespace pelage::sim
