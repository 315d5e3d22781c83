// Tiles of a still split over a render farm: `pelage render --tile I/N` renders band I
// of N (1-based) and `pelage merge` puts the bands back together. Band I covers the
// rows floor((I − 1)·H/N) to floor(I·H/N) − 1, every column: bands keep each tile's
// file one contiguous block of scanlines, and their heights differ by one row at most.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/image/image_output.h"

namespace pelage::renderer {

struct TileSpec {
    int index = 1, count = 1;   // tile `index` of `count`, 1-based
    std::string label() const;  // "I/N", as --tile takes it and pelage:tile records it
};

// "I/N" with 1 <= I <= N; throws pelage::InputError at field `flag` otherwise.
TileSpec parse_tile(const std::string &text, const std::string &flag = "--tile");

// The rows [*y0, *y1) of `tile` in an image `height` rows high. Throws
// pelage::InputError at field `flag` when the image has fewer rows than tiles.
void tile_rows(const TileSpec &tile, int height, int *y0, int *y1,
               const std::string &flag = "--tile");

// What a tile's EXR records besides a whole render's metadata: which tile it is ("I/N")
// and the samples its pixels took (decimal), from which `pelage merge` restores the
// whole image's pelage:mean_spp exactly.
inline constexpr const char *tile_attribute = "pelage:tile";
inline constexpr const char *tile_samples_attribute = "pelage:tile_samples";

// Rows [y0, y1) of `pixels`, an image `height` rows high, any width and channels.
std::vector<float> tile_pixels(const std::vector<float> &pixels, int height, int y0,
                               int y1);

// Makes `meta` (a whole render's) a tile's: the data window is rows [y0, y1) of the
// width × height display window; `samples` and `spp` are the tile's
// (RenderResult::region_samples, region_spp_done).
void describe_tile(const TileSpec &tile, int width, int height, int y0, int y1,
                   uint64_t samples, int spp, ImageMetadata *meta);

}  // namespace pelage::renderer
