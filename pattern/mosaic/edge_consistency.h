// Measuring Teo's "cracks" (Teo 2006 §6.3, Fig. 6.5): the two triangles on either side of
// an edge unfold the surface differently where it is curved, so points a hair apart
// across the edge may find different nearest cells. For each manifold edge we query
// points on it from both sides and classify disagreements:
//   * crack: the two unfoldings measure different distances to the competing cells —
//     inherent to flattening a curved surface, minimised by the unfolding choice;
//   * inconsistent: both sides measure the same distances yet disagree beyond a near-tie
//   —
//     a bug in the search (must be 0).
#pragma once

#include "pattern/mosaic/closest_cell.h"
#include "sim/mesh/mesh.h"

namespace pelage::pattern::mosaic {

struct EdgeConsistency {
    size_t samples = 0;
    size_t cracks = 0;
    size_t inconsistent = 0;
    double crack_rate() const { return samples ? double(cracks) / samples : 0.0; }
};

// `per_edge` points at fractions (k + 0.5) / per_edge along every manifold edge.
EdgeConsistency measure_edge_consistency(const sim::TriangleMesh &mesh,
                                         const sim::Crps &crps,
                                         const ClosestCellIndex &index, int per_edge = 3);

}  // namespace pelage::pattern::mosaic
