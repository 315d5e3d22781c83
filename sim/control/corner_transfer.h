// Carrying per-corner values from one mesh to another of the same shape: each corner of
// the target takes the value at the closest point of the source (barycentric
// interpolation of that triangle's corner values). The simulation may run on a copy of
// the input simplified to the cells' scale (sim/remesh/cell_scale_surface.h), which
// keeps neither vertex attributes nor UVs: regions that read them are resolved on the
// input and carried over this way.
#pragma once

#include <vector>

#include "sim/mesh/closest_point.h"
#include "sim/mesh/mesh.h"

namespace pelage::sim {

// For every corner of `target` (3 per triangle), the closest point of `source`
// (ClosestPointGrid, ranked by point: ties go to the lowest triangle id). Its `bary` is
// derived again from the point (barycentric_of in corner_transfer.cpp), so the values
// carried into the simulation keep their exact weights.
std::vector<MeshPoint> closest_source_points(const TriangleMesh &source,
                                             const TriangleMesh &target);

// Per-corner values of `source` (3 per triangle) at each target corner.
std::vector<double> transfer_corner_values(const std::vector<MeshPoint> &map,
                                           const std::vector<double> &source_values);

}  // namespace pelage::sim
