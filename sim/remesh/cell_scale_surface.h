// The surface a simulation runs on: the input mesh when its triangles are not much
// smaller than the cells, else a copy simplified to the cells' scale (simplify.h).
//
// The relaxation's neighbourhoods are built per triangle and reach r ≈ w_r·s (s the mean
// cell spacing), so their cost grows with triangles per cell; the pattern needs the
// surface only to the cells' scale. The input is simplified when its mean edge is
// shorter than the final cell spacing s = sqrt(A / m): edges shorter than s are
// collapsed (about 2 triangles per cell where the shape allows), and no collapse may move
// the surface farther than max_deviation_fraction of the bounding-box diagonal nor a
// tenth of s, so the pattern transfers back to the input
// (shader/clonal_mosaic/surface_transfer.h) well inside its 2 % tolerance.
#pragma once

#include <cstddef>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct CellScaleReport {
    bool simplified = false;
    size_t input_triangles = 0, output_triangles = 0;
    double cell_spacing = 0;     // s = sqrt(A / expected final cells)
    double input_mean_edge = 0;  // of the input
    double edge_length = 0;      // collapse threshold (0 when not simplified)
    double max_deviation = 0;    // bound on the distance from the input
    double bbox_diagonal = 0;    // of the input
};

inline constexpr double max_deviation_fraction = 0.002;

// The mesh to simulate on for `expected_cells` final cells over `area`; `report` says
// what was done. Returns the input unchanged when it is coarse enough.
TriangleMesh cell_scale_surface(const TriangleMesh &mesh, double area,
                                double expected_cells, CellScaleReport *report);

}  // namespace pelage::sim
