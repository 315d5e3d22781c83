// A triangle soup made from a clean mesh, as asset stores ship some animals: the mesh
// split into small edge-connected pieces, each with its own copies of its vertices moved
// by one small random vector, plus a few tiny pieces that touch nothing. Deterministic
// for a seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::test {

struct TriangleSoup {
    sim::TriangleMesh mesh;
    std::vector<uint32_t> piece;  // per triangle of `mesh`: its piece
    size_t pieces = 0;            // including the floating ones
    size_t floating = 0;          // the last pieces: one triangle each, off the surface
};

// Pieces of 1 to 3 triangles. Each piece's vertices move by one vector of length
// offset_relative times the bounding-box diagonal; two pieces that share a vertex of
// `source` get vectors at least min_separation_relative of the diagonal apart (so that
// a weld below it keeps them apart).
TriangleSoup make_triangle_soup(const sim::TriangleMesh &source, double offset_relative,
                                double min_separation_relative, uint64_t seed);

// `mesh` as an OFF file with every digit of its coordinates.
void write_off_exact(const std::string &path, const sim::TriangleMesh &mesh);

}  // namespace pelage::test
