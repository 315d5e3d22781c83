// Baking a mosaic into textures: every texel of a UV layout — the mesh's own UVs, or the
// CRPS atlas (atlas.h) — takes the pattern's look at its surface point, through the same
// mosaic::MosaicPattern search the renderer uses and the same footprint filter the
// clonal_mosaic shader applies to a camera hit (the nearest three cells blended over a
// band as wide as the footprint), with the texel's own footprint on the surface. So a
// texture render of the bake matches a render of the mosaic at the bake's resolution.
//
// UVs may span several UDIM tiles (Mari's numbering: 1001 + u tile + 10 v tile, u and
// v tiles 0…9); a triangle belongs to the tile of its UV centroid. Texels within
// `gutter` texels of a triangle but outside every triangle continue the surface across
// the chart's border: from the nearest point of the nearest triangle the texel's offset
// is walked over the surface (sim/crps/cell_walk.h), so across a seam it reaches the
// triangle on the far side and takes the pattern there — what bilinear and MIP-mapped
// lookups near the seam need. Farther texels take the mean colour of their nearest
// covered neighbours (alpha 0), so coarse MIP levels do not darken near charts.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "pattern/bake/atlas.h"
#include "pattern/mosaic/pattern.h"
#include "sim/crps/surface.h"

namespace pelage::pattern::bake {

struct BakeLayout {
    // The mesh the UVs belong to; its positions give each texel's footprint. It is the
    // pattern's simulation mesh (transfer == null) or another mesh of the same shape,
    // carried onto it by `transfer` (the pattern's own,
    // mosaic::MosaicPattern::transfer()).
    const sim::TriangleMesh *mesh = nullptr;
    std::vector<sim::Vec2d> corner_uvs;  // 3 per triangle of *mesh, OBJ convention
    const transfer::SurfaceTransfer *transfer = nullptr;
    int width = 0, height = 0;  // texels of each UDIM tile
    int gutter = 4;
};

struct BakedTile {
    int udim = 1001;
    // width × height × channels floats, rows top to bottom.
    std::vector<float> pixels;
};

struct BakeResult {
    // RGBA (A = 1 on triangles and their gutters), then the cell type, the stable cell
    // id and its founder's id (lineage) of the cell nearest the texel's centre — not
    // filtered; −1 where no triangle or gutter covers the texel.
    static constexpr int channels = 7;
    static std::vector<std::string> channel_names() {
        return {
            "R", "G", "B", "A", "shader.cell_type", "shader.cell_id", "shader.lineage"};
    }
    int width = 0, height = 0;
    std::vector<BakedTile> tiles;     // ascending UDIM
    size_t texels_inside = 0;         // centre inside a triangle
    size_t texels_gutter = 0;         // filled from the surface beyond a chart's border
    size_t texels_overlapped = 0;     // centre strictly inside two or more triangles
    size_t degenerate_triangles = 0;  // zero UV area: not baked
    size_t num_tiles = 0;
    double coverage() const {
        return num_tiles ? double(texels_inside) /
                               (double(num_tiles) * double(width) * double(height))
                         : 0.0;
    }
    double overlap_share() const {
        return texels_inside ? double(texels_overlapped) / double(texels_inside) : 0.0;
    }
};

// The UDIM tile of UV (u, v); throws std::invalid_argument when outside 1001…1100.
int udim_of(sim::Vec2d uv);

// The UDIM tiles a layout's triangles fall in (by UV centroid), ascending. Throws
// std::invalid_argument naming the triangle (and its source face) whose UVs lie
// outside the UDIM range.
std::vector<int> udim_tiles(const sim::TriangleMesh &mesh,
                            const std::vector<sim::Vec2d> &corner_uvs);

// Throws as udim_tiles() does, before baking anything. Each tile is handed to
// `on_tile` as soon as it is baked (so only one is held at a time) when given, else
// kept in the result's `tiles`.
BakeResult bake_layout(const mosaic::MosaicPattern &pattern, const BakeLayout &layout,
                       const std::function<void(BakedTile &&)> &on_tile = {});

struct BakedAtlas {
    Atlas atlas;
    BakeResult image;  // one tile, 1001
};

// A surface laid out by pack_atlas and baked: the simulation surface, or — when the
// pattern carries another mesh of its shape onto it (pattern.transfer()) and `render`
// is given — that mesh (built from the same file, so its triangles are the
// transfer's).
BakedAtlas bake_atlas(const mosaic::MosaicPattern &pattern, int width, int height,
                      int gutter = 4, const sim::Surface *render = nullptr);

}  // namespace pelage::pattern::bake
