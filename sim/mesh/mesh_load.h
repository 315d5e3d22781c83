// One call from a path (or a "procedural:..." spec) to a mesh ready for the CRPS: read,
// weld, drop degenerate triangles. Shared by every subcommand that takes --mesh.
#pragma once

#include <string>

#include "sim/mesh/mesh_clean.h"
#include "sim/mesh/mesh_io.h"

namespace pelage::sim {

struct MeshLoadReport {
    MeshReadStats read;
    MeshCleanStats clean;
    size_t raw_vertices = 0, raw_triangles = 0;
};

// "procedural:sphere:20x20" and friends (sim/mesh/procedural_mesh.h) need no file.
TriangleMesh load_mesh(const std::string &path_or_spec, MeshLoadReport *report = nullptr,
                       const MeshCleanOptions &clean = {});

}  // namespace pelage::sim
