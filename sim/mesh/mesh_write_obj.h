// Writing a mesh as Wavefront OBJ with per-corner UVs (`pelage bake --obj`), atomically.
#pragma once

#include <string>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

// corner_uvs: empty, or 3 per triangle in the mesh's corner order.
void write_obj(const std::string &path, const TriangleMesh &mesh,
               const std::vector<Vec2d> &corner_uvs, const std::string &comment = "");

}  // namespace pelage::sim
