// A mesh with its CRPS: what the simulation, the shader and the tools work on.
#pragma once

#include <string>

#include "sim/crps/crps.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::sim {

struct Surface {
    TriangleMesh mesh;
    Crps crps;
    MeshLoadReport load;
    double seconds_load = 0, seconds_topology = 0, seconds_crps = 0;
};

// Loads (sim/mesh/mesh_load.h), builds topology and CRPS, and times each stage.
Surface build_surface(const std::string &path_or_spec);
// The same for a mesh already in memory (its load report stays empty).
Surface build_surface(TriangleMesh mesh);

}  // namespace pelage::sim
