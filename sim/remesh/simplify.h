// A coarser copy of a mesh for the simulation to run on when the input's triangles are
// much smaller than the cells: the relaxation's neighbourhoods are built per triangle,
// so their cost grows with triangles per cell, while the pattern only needs the surface
// resolved at the cells' scale.
//
// Edges are collapsed shortest first (CGAL's Surface_mesh_simplification with Lindstrom
// & Turk's placement, "Fast and memory efficient polygonal simplification", 1998) until
// every edge is at least `edge_length` long. A collapse is refused when its new vertex
// would lie farther than `max_deviation` from the input surface (CGAL's bounded-distance
// placement; the bound is on vertices, not on whole faces) or when it would turn a
// face's normal by more than 90° (CGAL's bounded normal change filter), so thin parts,
// ears and horns stay where they are at the price of keeping more triangles there. The
// topology is kept (link condition); a vertex where two fans meet only at a point is
// split first. Plain double arithmetic: the exact-predicate kernel's fallbacks made the
// distance tests ten times slower without changing the result on the sample meshes.
#pragma once

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct SimplifyOptions {
    double edge_length = 0;    // collapse edges shorter than this
    double max_deviation = 0;  // the result stays within this distance of the input
    // The surface the bound refers to when the mesh is itself a reduction of it
    // (vertex_clustering.h); null: the mesh.
    const TriangleMesh *reference = nullptr;
};

// The simplified mesh (positions and triangles only; corner normals and UVs are
// dropped, source_face is the triangle's index). Returns the input's geometry
// unchanged when no edge is shorter than edge_length.
TriangleMesh simplify(const TriangleMesh &mesh, const SimplifyOptions &options);

// The largest distance from a vertex of `from` that a triangle uses to the surface of
// `to` (CGAL's AABB tree): the side of the two-sided (Hausdorff) distance that
// simplify()'s bound on its own vertices does not cover, where a thin part collapsed to a
// stub leaves the input's vertices behind.
double max_vertex_distance(const TriangleMesh &from, const TriangleMesh &to);

// The mean edge length of a mesh (each triangle's three edges; shared edges twice).
double mean_edge_length(const TriangleMesh &mesh);

}  // namespace pelage::sim
