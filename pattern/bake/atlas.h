// A UV atlas of a mesh made of its CRPS reference triangles: each is an undistorted copy
// of its face (Teo 2006 §4.2), so the atlas has no stretching at all. Used by `pelage
// bake` to turn a mosaic into an ordinary texture — the texture-mapping baseline of
// Teo's Table 7.9, and an export any DCC can read.
//
// Charts: edge-connected triangles laid flat by unfolding each added triangle about the
// edge it shares with the chart (its reference shape, rigidly moved, so still
// undistorted). A chart grows from its seed, nearest candidate first (so it stays
// compact), and refuses a triangle whose unfolded copy would overlap the chart or whose
// normal turns more than `max_chart_angle_deg` from the seed's: on a curved part the
// unfolding opens gaps around the vertices, which waste texels and pack poorly. Texels
// in such a gap lie within the bake's gutter of both sides and are filled from the
// surface (bake.h), like any other seam.
//
// Packing: each chart is turned to its least-area bounding box (one side along a hull
// edge), rasterised with half a gutter around its triangles, and placed, largest
// first, at the first free position (least row, then column) of an occupancy bitmap in
// either of two orientations, as xatlas packs its charts: small charts fill the notches
// of large ones. The scale is the largest at which every chart fits (bisection on a
// coarse grid, refined on the fine one).
#pragma once

#include <array>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::pattern::bake {

struct AtlasOptions {
    int gutter = 4;  // texels kept free around each chart (the bake fills them)
    double max_chart_angle_deg = 30;
};

struct Atlas {
    int width = 0, height = 0;
    double texels_per_unit = 0;  // the common scale: every face keeps its shape and size
    size_t num_charts = 0;
    // Per triangle, its corners in texel coordinates (x right, y down).
    std::vector<std::array<sim::Vec2d, 3>> corners;
    // UV of corner c of triangle t, OBJ convention (v = 0 at the bottom of the image).
    sim::Vec2d uv(sim::TriId t, int c) const {
        const sim::Vec2d p = corners[t][c];
        return {p.x / width, 1.0 - p.y / height};
    }
    // The share of the atlas's area inside triangles.
    double coverage() const;
};

// Throws std::invalid_argument when even a tiny scale cannot fit (resolution too small
// for the number of charts and their gutters).
Atlas pack_atlas(const sim::Crps &crps, int width, int height,
                 const AtlasOptions &options = {});

}  // namespace pelage::pattern::bake
