// The topology of a triangle mesh as a simplification must keep it: what the greedy
// collapse (greedy_collapse.h) checks its result against.
#pragma once

#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

// A vertex where fans of faces meet only at a point counts once per fan, as CGAL's
// edge collapse splits it (simplify.h); unused vertices do not count.
struct SurfaceTopology {
    bool edge_manifold = false;  // every edge on one face or two oriented alike
    long pinched = 0;            // vertices with more than one fan
    long euler = 0;              // V − E + F, V counting fans
    long components = 0;         // faces connected across shared edges
    long boundary_loops = 0;

    bool operator==(const SurfaceTopology &) const = default;
};

// The topology, and per vertex its number of fans and whether it is on a boundary.
struct TopologyDetail {
    SurfaceTopology top;
    std::vector<uint32_t> fans;
    std::vector<char> on_boundary;
};
TopologyDetail analyse_topology(const TriangleMesh &mesh);

SurfaceTopology surface_topology(const TriangleMesh &mesh);

}  // namespace pelage::sim
