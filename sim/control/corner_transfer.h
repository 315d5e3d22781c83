// Carrying per-corner values from one mesh to another of the same shape: each corner of
// the target takes the value at the closest point of the source (barycentric
// interpolation of that triangle's corner values). The simulation may run on a copy of
// the input simplified to the cells' scale (sim/remesh/cell_scale_surface.h), which
// keeps neither vertex attributes nor UVs: regions that read them are resolved on the
// input and carried over this way.
#pragma once

#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct ClosestSource {
    TriId tri = 0;
    Vec3d b;  // barycentric coordinates of the closest point in `tri`
};

// For every corner of `target` (3 per triangle), the closest point of `source`, found
// through a uniform grid of the source's triangles. Ties go to the lowest triangle id.
std::vector<ClosestSource> closest_source_points(const TriangleMesh &source,
                                                 const TriangleMesh &target);

// Per-corner values of `source` (3 per triangle) at each target corner.
std::vector<double> transfer_corner_values(const std::vector<ClosestSource> &map,
                                           const std::vector<double> &source_values);

}  // namespace pelage::sim
