// Writing a mesh as Wavefront OBJ with per-corner UVs and the mesh's own per-corner
// normals (`pelage bake --obj`), atomically. Numbers are written in their shortest form
// that reads back to the same double, so UVs and normals survive a round trip exactly.
#pragma once

#include <string>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

// corner_uvs: empty, or 3 per triangle in the mesh's corner order. The mesh's
// corner_normals, when it has them, are written too (vn, in the face's third slot).
void write_obj(const std::string &path, const TriangleMesh &mesh,
               const std::vector<Vec2d> &corner_uvs, const std::string &comment = "");

}  // namespace pelage::sim
