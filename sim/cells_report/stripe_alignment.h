// How well a pattern's stripes follow the anisotropy field: at every cell on an F/B
// boundary, the local direction of the boundary against the field's direction there.
//
// The boundary's direction comes from a structure tensor of the type indicator χ (1 on
// F): every cell's gradient g = Σ (χ_q − χ_p)(q − p) over its neighbours q closer than
// 1.5·sqrt(A/m) (the Voronoi neighbours of pattern_stats.h), and the sum of g·gᵀ over
// the cells within `window` cell spacings, all laid out in the cell's triangle frame by
// unfolding across edges. Its dominant eigenvector is the boundary's normal and the
// stripe runs perpendicular to it; the coherence (λ1 − λ2)/(λ1 + λ2) is near 1 along a
// straight boundary and near 0 where boundaries turn every way (small round spots). A
// field is an axis here (the SG01 anisotropy does not depend on A's sign), so angles are
// in [0°, 90°]. On straight stripes of a jittered lattice the median error is about 2°;
// boundaries that curve within the window (radius of curvature below ~10 spacings) read
// a few degrees more.
#pragma once

#include <vector>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/tangent_field.h"

namespace pelage::sim {

struct StripeAlignment {
    size_t samples = 0;                 // boundary cells on triangles with a field vector
    double median = 0, q1 = 0, q3 = 0;  // degrees between stripe and field
    double coherence = 0;               // median coherence of the samples
    std::vector<double> angles;         // per sample, in cell order
};

// `crps` is the surface the cells were grown on (the same triangles as `data`).
StripeAlignment measure_stripe_alignment(const CellsData &data, const Crps &crps,
                                         const TangentField &field, double window = 3.0);

}  // namespace pelage::sim
