// A UV atlas of a mesh's CRPS reference triangles: each is an undistorted copy of its
// face (Teo 2006 §4.2), so packing them side by side gives a texture map with no
// stretching at all. Used by `pelage bake` to turn a mosaic into an ordinary texture —
// the texture-mapping baseline of Teo's Table 7.9, and an export any DCC can read.
#pragma once

#include <array>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::shader::clonal_mosaic {

struct AtlasTriangle {
    // Atlas position (in texels, y down) of local CRPS point p: A·p + offset.
    float a00, a01, a10, a11, ox, oy;
    std::array<sim::Vec2d, 3> corners;  // atlas texel coordinates of the three corners
};

struct Atlas {
    int resolution = 0;
    double texels_per_unit =
        0;  // the common scale: every face keeps its shape and size ratio
    std::vector<AtlasTriangle> triangles;
    // UV of corner c of triangle t, OBJ convention (v = 0 at the bottom of the image).
    sim::Vec2d uv(sim::TriId t, int c) const {
        const sim::Vec2d p = triangles[t].corners[c];
        return {p.x / resolution, 1.0 - p.y / resolution};
    }
};

// Shelf-packs the reference triangles (longest edge along x) into a resolution² atlas
// with `gutter` texels around each, at the largest common scale that fits. Throws
// std::invalid_argument when even a tiny scale cannot fit (resolution too small).
Atlas pack_atlas(const sim::Crps &crps, int resolution, int gutter = 2);

}  // namespace pelage::shader::clonal_mosaic
