// A cheap first reduction of a mesh far finer than its simplification's target (a hero
// mesh of millions of triangles for cells many triangles wide), before CGAL's edge
// collapse (simplify.h) does the rest. CGAL pays a priority queue, an edge profile and an
// AABB-tree query of the input per collapse: the 1.5 M-triangle cow spent ~170 s there
// to come down to 10 000 triangles. Here edges shorter than `edge_length` are collapsed
// greedily, in face order, a vertex into a neighbour that stays where it is, with no
// queue and no tree: every vertex left is an input vertex, so CGAL's bound on vertices
// holds trivially, and the input vertices a vertex stands for are kept within
// max_distance of the faces around it (a tail folded into a stub has its vertices far
// from them).
//
// A collapse is made only when it keeps the surface as it is (Dey et al.'s link
// condition, "Topology preserving edge contraction", 1999: the two ends share exactly
// the neighbours of the faces on the edge), turns no face by more than max_turn_degrees
// nor flattens one, and touches no boundary or pinched vertex it would move, nor a
// pole of more than max_valence faces (the cost of a try grows with the ring). The
// result's topology is then checked against the input's (surface_topology.h); a mesh
// whose edges are not manifold is not reduced.
#pragma once

#include <optional>
#include <string>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct GreedyCollapseOptions {
    double edge_length = 0;   // collapse edges shorter than this
    double max_distance = 0;  // from every input vertex to the result
    double max_turn_degrees = 45;
    int max_passes = 8;       // over all faces; a pass that collapses nothing ends it
    size_t max_valence = 64;  // faces around either end, about; poles are left alone
};

// The reduced mesh (positions and triangles; source_face is the input triangle each face
// was), or none, saying why in *refused.
std::optional<TriangleMesh> greedy_collapse(const TriangleMesh &mesh,
                                            const GreedyCollapseOptions &options,
                                            std::string *refused = nullptr);

}  // namespace pelage::sim
