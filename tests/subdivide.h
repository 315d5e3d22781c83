// Subdivided copies of a mesh for the tests of rendering on another mesh of the same
// shape: every triangle split in four at its edge midpoints (the same surface, exactly),
// or Loop's smooth subdivision (C. Loop, "Smooth subdivision surfaces based on
// triangles", 1987; Warren's weights), whose vertices move off the original surface.
// Child 4t + k of the result lies on triangle t of the input.
#pragma once

#include "sim/mesh/mesh.h"

namespace pelage::test {

enum class Subdivision { midpoint, loop };
sim::TriangleMesh subdivide(const sim::TriangleMesh &mesh, Subdivision kind);

}  // namespace pelage::test
