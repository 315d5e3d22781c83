// What exact geodesic propagation needs to know about a surface, on top of the CRPS:
// for every triangle edge the triangle across it and the rigid map into that triangle's
// frame, and for every vertex whether shortest paths may bend around it.
//
// A shortest path on a polyhedral surface is a straight line in the unfolding of the
// triangles it crosses, and may pass through a vertex only where the total angle around
// it is at least 2π (a saddle vertex) or on the boundary (Mitchell, Mount & Papadimitriou
// 1987, "The discrete geodesic problem", §2). Such vertices become pseudo-sources of the
// propagation (window_propagation.h). Around a convex vertex (angle sum below 2π) paths
// never bend.
//
// Saddle vertices whose excess angle is below `flat_tolerance` are treated as flat: the
// paths they would bend change distances by at most the excess angle times the distance
// from the vertex, and ignoring them saves most pseudo-sources on noisy meshes, where
// half of the vertices are marginally saddle.
#pragma once

#include <array>
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
    bool pseudo_source(VertId v) const { return m_pseudo_source[v] != 0; }
    double angle_sum(VertId v) const { return m_angle_sum[v]; }
    size_t num_pseudo_sources() const { return m_num_pseudo_sources; }
    size_t num_vertices() const { return m_angle_sum.size(); }

  private:
    const Crps *m_crps;
    std::vector<std::array<EdgeLink, 3>> m_links;
    std::vector<double> m_angle_sum;
    std::vector<uint8_t> m_pseudo_source;
    size_t m_num_pseudo_sources = 0;
};

}  // namespace pelage::sim
