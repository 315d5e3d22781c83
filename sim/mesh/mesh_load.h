// One call from a mesh reference (a path, "PATH#OBJECT", or a "procedural:..." spec) to a
// mesh ready for the CRPS: read, weld, drop degenerate triangles. Shared by every
// subcommand that takes --mesh and by the renderer.
#pragma once

#include <string>

#include "sim/mesh/mesh_clean.h"
#include "sim/mesh/mesh_io.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::sim {

struct MeshLoadReport {
    MeshReadStats read;
    MeshCleanStats clean;
    size_t raw_vertices = 0, raw_triangles = 0;
};

// "procedural:sphere:20x20" and friends (sim/mesh/procedural_mesh.h) need no file;
// "zoo.glb#giraffe" is the object "giraffe" of zoo.glb (sim/mesh/mesh_objects.h). A
// file of several objects loaded whole prints one note to stderr (once per file and
// process) saying how many were merged and how to select one.
TriangleMesh load_mesh(const std::string &path_or_spec, MeshLoadReport *report = nullptr,
                       const MeshCleanOptions &clean = {});

}  // namespace pelage::sim
