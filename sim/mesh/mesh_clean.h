// Turning a mesh as stored into one the CRPS can be built on: duplicate vertices welded,
// zero-area triangles dropped. Both are counted so tools can report them.
#pragma once

#include <array>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct MeshCleanOptions {
    // Vertices closer than weld_relative * (bounding-box diagonal) become one vertex.
    // Store meshes exported piece by piece (a triangle soup: every face or island with
    // its own copies of its vertices) carry copies that differ by the rounding of each
    // piece's float transform, about 1e-7 of the coordinates and so up to ~1e-6 of the
    // diagonal: 1e-5 stitches them with a margin of ten. It stays far below any
    // modelled gap: the mean edge of a 100 000-triangle animal is about 4e-3 of the
    // diagonal, and lips, eyelids or toes apart at rest by less than a hundredth of an
    // edge would not read as apart in any render (what touches at rest and parts in a
    // pose keeps its own motion through MeshCleanStats::source_corners).
    double weld_relative = 1e-5;
    // Boundary vertices of different pieces closer than stitch_relative * diagonal (and
    // than a third of their shortest edges) become one: a triangle soup's pieces, cut
    // apart with copies that moved slightly, join again (mesh_clean.cpp stitch_pieces).
    double stitch_relative = 1e-3;
    // Triangles with area below area_relative * diagonal^2 are degenerate.
    double area_relative = 1e-14;
};

struct MeshCleanStats {
    size_t vertices_welded = 0;     // vertices merged into another
    size_t vertices_stitched = 0;   // boundary vertices joined to another piece's
    size_t degenerate_dropped = 0;  // zero-area triangles removed
    size_t unused_vertices = 0;     // vertices no triangle references (kept, harmless)
    // For each output vertex, the input vertex it is (the lowest index of a welded
    // group): what carries a pose given per input vertex, such as a skinned animation's,
    // to the cleaned mesh.
    std::vector<VertId> source_vertex;
    // For each output triangle, its corners as the input numbered them (before welding):
    // vertices that coincide at rest but move apart in a pose (seams, touching parts)
    // keep their own motion this way.
    std::vector<std::array<VertId, 3>> source_corners;
};

// Throws InputError(source_path, ...) when nothing is left (an empty mesh).
TriangleMesh clean_mesh(const TriangleMesh &in, const std::string &source_path,
                        const MeshCleanOptions &opt = {},
                        MeshCleanStats *stats = nullptr);

}  // namespace pelage::sim
