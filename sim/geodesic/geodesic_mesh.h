// What exact geodesic propagation needs to know about a surface, on top of the CRPS:
// for every triangle edge the triangle across it and the rigid map into that triangle's
// frame, and for every vertex whether shortest paths may bend around it.
//
// A shortest path on a polyhedral surface is a straight line in the unfolding of the
// triangles it crosses, and may pass through a vertex only where the total angle around
// it is at least 2π (a saddle vertex) or on the boundary (Mitchell, Mount & Papadimitriou
// 1987, "The discrete geodesic problem", §2). Such vertices become pseudo-sources of the
// propagation (window_propagation.h). Around a convex vertex (angle sum below 2π) paths
// never bend. A pinch vertex (fans that share only the vertex, e.g. two file vertices
// welded into one) becomes one vertex per fan, so no path crosses from one fan to the
// other through it; vertex ids here are the mesh's plus those extra copies.
//
// Saddle vertices whose excess angle is below `flat_tolerance` are treated as flat: the
// paths they would bend change distances by at most the excess angle times the distance
// from the vertex, and ignoring them saves most pseudo-sources on noisy meshes, where
// half of the vertices are marginally saddle.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::sim {

struct GeodesicMeshOptions {
    double flat_tolerance = 0;  // radians of excess angle treated as flat
};

class GeodesicMesh {
  public:
    struct EdgeLink {
        TriId across = invalid_id;   // invalid_id on a boundary or non-manifold edge
        uint8_t edge_in_across = 0;  // the same edge's index in `across`
        RigidMap2 to_across;         // this triangle's frame -> across's frame
    };

    explicit GeodesicMesh(const Crps &crps, const GeodesicMeshOptions &options = {});

    const Crps &crps() const { return *m_crps; }
    // Edge k joins corners k and (k + 1) % 3.
    const EdgeLink &link(TriId t, int k) const { return m_links[t][k]; }
    // The vertices at t's corners (a pinch vertex's copy for t's fan).
    const std::array<VertId, 3> &corners(TriId t) const { return m_corners[t]; }
    // The triangles around vertex v.
    std::span<const TriId> fan_of(VertId v) const {
        return {m_fan.data() + m_fan_row[v], m_fan_row[v + 1] - m_fan_row[v]};
    }
    bool pseudo_source(VertId v) const { return m_pseudo_source[v] != 0; }
    double angle_sum(VertId v) const { return m_angle_sum[v]; }
    size_t num_pseudo_sources() const { return m_num_pseudo_sources; }
    size_t num_vertices() const { return m_angle_sum.size(); }

  private:
    const Crps *m_crps;
    std::vector<std::array<EdgeLink, 3>> m_links;
    std::vector<std::array<VertId, 3>> m_corners;
    std::vector<uint32_t> m_fan_row;
    std::vector<TriId> m_fan;
    std::vector<double> m_angle_sum;
    std::vector<uint8_t> m_pseudo_source;
    size_t m_num_pseudo_sources = 0;
};

}  // namespace pelage::sim
