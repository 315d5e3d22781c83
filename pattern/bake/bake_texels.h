// Where a bake layout's texels lie (bake.h): each triangle in its UDIM tile's texel
// coordinates, and per texel of a tile the triangle that owns it — the nearest one
// within the gutter.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "pattern/bake/bake.h"

namespace pelage::pattern::bake {

// A layout triangle in its tile's texel coordinates (x right, y down), with the affine
// map from texel offsets to barycentric coordinates and to surface displacements.
struct TexelTriangle {
    std::array<sim::Vec2d, 3> p;
    double i00 = 0, i01 = 0, i10 = 0, i11 = 0;  // inverse of [p1 - p0, p2 - p0]
    sim::Vec3d jx, jy;      // surface displacement per texel along x and y
    float footprint = 0;    // the texel's width on the surface (pattern units)
    double x0, x1, y0, y1;  // bounding box
    bool valid = false;

    sim::Vec3d barycentric(sim::Vec2d q) const {
        const sim::Vec2d r = q - p[0];
        const double b1 = i00 * r.x + i01 * r.y, b2 = i10 * r.x + i11 * r.y;
        return {1 - b1 - b2, b1, b2};
    }
    // Distance from q to the triangle (0 inside) and the barycentrics of its nearest
    // point.
    double distance_to(sim::Vec2d q, sim::Vec3d *b_nearest) const;
};

// The tile of triangle t (its UV centroid's), checking every corner's range; throws
// std::invalid_argument naming the triangle and its source face.
int tile_of(const sim::TriangleMesh &mesh, const sim::Vec2d *uv, sim::TriId t);

struct TexelLayout {
    std::vector<TexelTriangle> tris;               // per triangle of the layout's mesh
    std::map<int, std::vector<uint32_t>> by_tile;  // valid triangles by UDIM, by id
    size_t degenerate_triangles = 0;               // zero UV area: not valid
};

// Every triangle of the layout in its tile's texel coordinates, with its gutter in its
// bounding box.
TexelLayout lay_out_texels(const BakeLayout &layout);

// Per texel of one W × H tile (rows top to bottom), its owner: the nearest triangle
// within the gutter, the first one by id among those that hold its centre.
struct TexelOwners {
    std::vector<float> dist;               // to the owner; infinite without one
    std::vector<uint32_t> owner;           // sim::invalid_id without one
    std::vector<uint8_t> strictly_inside;  // triangles holding the centre, up to 255
};

// The owners of a tile's texels among `tile_tris` (ascending ids); bands of rows in
// parallel.
TexelOwners find_owners(const std::vector<TexelTriangle> &tris,
                        const std::vector<uint32_t> &tile_tris, int W, int H,
                        double gutter);

}  // namespace pelage::pattern::bake
