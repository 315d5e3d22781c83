// Baking a mosaic into a texture: every texel of the CRPS atlas (atlas.h) takes the
// colour of the nearest cell at its surface point — the same MosaicPattern search the
// renderer uses. Texels within `gutter` of a triangle take its nearest surface point, so
// filtered lookups near seams do not bleed the background in.
#pragma once

#include "shader/clonal_mosaic/atlas.h"
#include "shader/clonal_mosaic/pattern.h"

namespace pelage::shader::clonal_mosaic {

struct BakedPattern {
    Atlas atlas;
    // res × res texels, rows top to bottom: RGBA (A = 1 where a triangle or its gutter
    // covers the texel) followed by cell type and stable cell id (−1 when uncovered).
    static constexpr int channels = 6;
    std::vector<float> pixels;
    size_t texels_inside = 0, texels_gutter = 0;
};

BakedPattern bake_pattern(const MosaicPattern &pattern, int resolution, int gutter = 2);

}  // namespace pelage::shader::clonal_mosaic
