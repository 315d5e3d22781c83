// The mean colour of what a matte covers: for each name of one Cryptomatte layer of an
// EXR (the cell types of `CryptoType`, say), the mean linear RGB of the beauty over the
// pixels that name's matte covers fully. Comparing a furry render's type colours with
// the bare skin's says whether the fur keeps the pattern's colours (docs/guide/fur.md);
// comparing a render with the same scene in grey says what colour each type shows under
// the scene's light (`pelage bench preset-colour`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/vec.h"

namespace pelage::renderer {

struct Matte;

struct MatteColour {
    std::string name;
    Rgb mean{0, 0, 0};  // linear RGB; 0 when no pixel is covered
    size_t pixels = 0;  // the pixels counted (see `erode` below)
};

// One entry per name of `layer` ("CryptoType" or "type"), in the manifest's order.
// A pixel counts when its coverage, and that of every pixel within `erode` pixels of it
// (a (2·erode + 1)² square), is at least min_coverage: the beauty is filtered over about
// 1.5 pixels (film.filter), so a pixel fully covered but next to another type shows some
// of that type's colour, much of it when the two differ thirtyfold (a black spot on a
// pale ground); erode 1 keeps only pixels whose whole filter footprint is covered.
// Throws pelage::InputError naming the file when it cannot be read, has no RGB or no
// such layer.
std::vector<MatteColour> mean_colour_by_matte(const std::string &exr,
                                              const std::string &layer,
                                              float min_coverage = 0.99f, int erode = 0);

// The same names, pixels and means for two renders of one scene that differ only in
// colour (same camera, cells and samples): the pixels are chosen on `exr`'s mattes and
// both images are averaged over them, so the two means see the same light. `other` must
// have `exr`'s size.
struct MatteColourPair {
    std::string name;
    Rgb mean{0, 0, 0}, other_mean{0, 0, 0};
    size_t pixels = 0;
};
std::vector<MatteColourPair> mean_colours_by_matte(const std::string &exr,
                                                   const std::string &other,
                                                   const std::string &layer,
                                                   float min_coverage, int erode);

// The pixels of `m` counted as above (1) or not (0), row by row.
std::vector<uint8_t> matte_interior(const Matte &m, float min_coverage, int erode);

}  // namespace pelage::renderer
