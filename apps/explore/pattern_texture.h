// The pattern as the explorer's 3D view shows it: a texture of cell types, whose every
// texel holds the type of the cell nearest its point on the surface, found by the
// renderer's own closest-cell search (pattern/mosaic/closest_cell.h). The page maps types
// to colours itself, so restyling a type's colour repaints without a new texture.
//
// Layout: each triangle of the simulation surface gets a square tile of k × k texels
// whose lower-left half holds it (corner 0 at the tile's first texel centre, corner 1
// along x, corner 2 along y), k proportional to its longest edge, so texels are about
// the same size on the surface everywhere. Tiles are placed on shelves, largest first;
// the texel size is the smallest that fits the texture. A texel stands for the sample at
// its centre, which the view reads with nearest filtering: every fragment takes the type
// at the nearest sample of its own triangle, so no tile bleeds into another.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "pattern/transfer/surface_transfer.h"
#include "sim/cells_io/cells_file.h"
#include "sim/crps/crps.h"
#include "sim/mesh/mesh.h"

namespace pelage::renderer::explore {

struct TypeTextureLayout {
    int size = 0;                   // size × size texels, row y at v = (y + 0.5) / size
    double texel_length = 0;        // on the surface: the tiles' longest edge per texel
    std::vector<float> corner_uvs;  // u, v of each triangle's three corners (6 floats)
    // One per sample: its texel (y · size + x), triangle and barycentric point (b1, b2)
    // (the point v0 + b1 (v1 − v0) + b2 (v2 − v0)).
    std::vector<uint32_t> texel;
    std::vector<sim::TriId> tri;
    std::vector<float> b1, b2;
    // The rest of each tile, (texel, sample's texel): a copy of the nearest sample on the
    // triangle's long edge. A multisampled fragment at a triangle's border may read just
    // outside the triangle's half of its tile.
    std::vector<std::pair<uint32_t, uint32_t>> fill;
};

// `size` ≥ 2 × √(triangles) so that every triangle gets a tile of at least 2 × 2 texels;
// throws std::invalid_argument otherwise.
TypeTextureLayout layout_type_texture(const sim::TriangleMesh &mesh, int size);

// Where each sample of the layout lies on another surface of the same shape (a
// simplified or refined copy), as the renderer carries its mesh onto the one the cells
// were grown on (pattern/transfer/surface_transfer.h).
using SampleTargets = std::vector<pattern::transfer::SurfaceTransfer::Target>;
SampleTargets map_samples(const TypeTextureLayout &layout,
                          const pattern::transfer::SurfaceTransfer &transfer);

// Texel value: the type index of the nearest cell (255 outside every triangle, or where
// no cell is reachable). `cells` lie on `crps`'s triangles: the layout's mesh, or the
// surface `targets` (map_samples) place the samples on.
constexpr uint8_t no_type = 255;
std::vector<uint8_t> type_texture(const TypeTextureLayout &layout, const sim::Crps &crps,
                                  const sim::CellsData &cells,
                                  const SampleTargets *targets = nullptr);

}  // namespace pelage::renderer::explore
