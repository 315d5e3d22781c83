// The mean colour of what a matte covers: for each name of one Cryptomatte layer of an
// EXR (the cell types of `CryptoType`, say), the mean linear RGB of the beauty over the
// pixels that name's matte covers fully. Comparing a furry render's type colours with
// the bare skin's says whether the fur keeps the pattern's colours (docs/guide/fur.md).
#pragma once

#include <string>
#include <vector>

#include "sim/core/vec.h"

namespace pelage::renderer {

struct MatteColour {
    std::string name;
    Rgb mean{0, 0, 0};  // linear RGB; 0 when no pixel is covered
    size_t pixels = 0;  // the pixels whose coverage is at least min_coverage
};

// One entry per name of `layer` ("CryptoType" or "type"), in the manifest's order.
// Throws pelage::InputError naming the file when it cannot be read, has no RGB or no
// such layer.
std::vector<MatteColour> mean_colour_by_matte(const std::string &exr,
                                              const std::string &layer,
                                              float min_coverage = 0.99f);

}  // namespace pelage::renderer
