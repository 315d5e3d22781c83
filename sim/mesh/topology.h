// Connectivity of a cleaned triangle mesh: edges with their faces, vertex fans (one-ring
// of faces), and per-triangle primary (edge-sharing) and secondary (vertex-only)
// neighbours, all in compact CSR arrays. Also a consistent orientation:
// the CRPS unfolds neighbours with rotations only, which needs all faces of a component
// to agree on which side is "up".
#pragma once

#include <array>
#include <span>
#include <vector>

#include "sim/core/check.h"
#include "sim/mesh/mesh.h"

namespace pelage::sim {

using EdgeId = uint32_t;

struct Topology {
    // --- Edges: endpoints (v0 < v1) and the faces around each (CSR) ---
    std::vector<std::array<VertId, 2>> edge_vertices;
    std::vector<uint32_t> edge_face_row;  // size num_edges + 1
    std::vector<TriId> edge_faces;
    // tri_edges[t][k] joins corners k and (k + 1) % 3 of triangle t.
    std::vector<std::array<EdgeId, 3>> tri_edges;

    // --- Vertex fans (CSR). Ordered by walking across edges where the vertex is
    //     manifold (fan_ordered[v] = 1); in id order otherwise. ---
    std::vector<uint32_t> fan_row;  // size num_vertices + 1
    std::vector<TriId> fan;
    std::vector<uint8_t> fan_ordered;

    // --- Triangle neighbours (CSR): nbr[nbr_row[t] .. nbr_row[t] + num_primary[t]) share
    //     an edge with t, the rest of the row shares only a vertex. Sorted by id. ---
    std::vector<uint32_t> nbr_row;  // size num_triangles + 1
    std::vector<TriId> nbr;
    std::vector<uint8_t> num_primary;

    // --- Orientation: flipped[t] = 1 when t's winding disagrees with its component ---
    std::vector<uint8_t> flipped;
    std::vector<uint32_t> component;  // connected component (through manifold edges)

    // --- Counts for reports ---
    size_t boundary_edges = 0;       // one face
    size_t nonmanifold_edges = 0;    // three or more faces
    size_t nonorientable_edges = 0;  // two faces that disagree even after reorientation
    size_t nonmanifold_vertices = 0;
    size_t faces_reoriented = 0;
    size_t num_components = 0;

    size_t num_edges() const { return edge_vertices.size(); }
    std::span<const TriId> faces_of_edge(EdgeId e) const {
        PELAGE_DCHECK(size_t(e) + 1 < edge_face_row.size());
        return {edge_faces.data() + edge_face_row[e],
                edge_face_row[e + 1] - edge_face_row[e]};
    }
    std::span<const TriId> fan_of(VertId v) const {
        PELAGE_DCHECK(size_t(v) + 1 < fan_row.size());
        return {fan.data() + fan_row[v], fan_row[v + 1] - fan_row[v]};
    }
    std::span<const TriId> neighbours(TriId t) const {
        PELAGE_DCHECK(size_t(t) + 1 < nbr_row.size());
        return {nbr.data() + nbr_row[t], nbr_row[t + 1] - nbr_row[t]};
    }
    std::span<const TriId> primary_neighbours(TriId t) const {
        PELAGE_DCHECK(t < num_primary.size() && size_t(t) + 1 < nbr_row.size());
        return {nbr.data() + nbr_row[t], num_primary[t]};
    }
    bool is_boundary(EdgeId e) const {
        return edge_face_row[e + 1] - edge_face_row[e] == 1;
    }
    bool is_manifold(EdgeId e) const {
        return edge_face_row[e + 1] - edge_face_row[e] == 2;
    }
    // The face across edge k of t, or invalid_id on a boundary or non-manifold edge.
    TriId across(TriId t, int k) const;
};

Topology build_topology(const TriangleMesh &mesh);

// Mean length of the mesh's (unique) edges: the natural unit for radii on the surface.
double mean_edge_length(const TriangleMesh &mesh, const Topology &topo);

}  // namespace pelage::sim
