// Reading meshes from disk: OFF (our own parser) and OBJ (tinyobjloader). Readers throw
// pelage::InputError naming the file and line; they never return a half-read mesh.
#pragma once

#include <string>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct MeshReadStats {
    size_t polygons_triangulated = 0;  // faces with more than 3 corners, fanned
};

// Dispatches on the extension (.off, .obj; case-insensitive). The mesh is returned as
// stored in the file: call clean_mesh() (sim/mesh/mesh_clean.h) before building topology.
TriangleMesh read_mesh(const std::string &path, MeshReadStats *stats = nullptr);

TriangleMesh read_off(const std::string &path, MeshReadStats *stats = nullptr);
TriangleMesh read_obj(const std::string &path, MeshReadStats *stats = nullptr);

}  // namespace pelage::sim
