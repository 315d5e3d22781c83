// Subdivided copies of a mesh, for measuring how costs grow with mesh density and for
// rendering a pattern on another mesh of its shape: every triangle split in four at its
// edge midpoints (the same surface, exactly), or Loop's smooth subdivision (C. Loop,
// "Smooth subdivision surfaces based on triangles", 1987; Warren's weights), whose
// vertices move off the original surface. Child 4t + k of the result lies on triangle t
// of the input.
#pragma once

#include "sim/mesh/mesh.h"

namespace pelage::sim {

enum class Subdivision { midpoint, loop };
TriangleMesh subdivide(const TriangleMesh &mesh, Subdivision kind);

}  // namespace pelage::sim
