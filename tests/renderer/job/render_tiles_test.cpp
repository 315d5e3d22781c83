// Tiles of a still: "I/N" parsing, the bands covering every row once, and cropping.
#include "renderer/job/render_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

TEST(RenderTiles, ParsesOneBasedTiles) {
    const TileSpec t = parse_tile("3/16");
    EXPECT_EQ(t.index, 3);
    EXPECT_EQ(t.count, 16);
    EXPECT_EQ(t.label(), "3/16");
    EXPECT_EQ(parse_tile("1/1").label(), "1/1");
    for (const std::string bad :
         {"", "3", "/4", "3/", "0/4", "5/4", "-1/4", "1/-4", "1/0", " 1/4", "1/4 ",
          "1//4", "a/4", "1/4x", "99999999999/4"}) {
        try {
            parse_tile(bad);
            ADD_FAILURE() << "\"" << bad << "\" accepted";
        } catch (const InputError &e) {
            EXPECT_EQ(e.field(), "--tile") << bad;
        }
    }
}

TEST(RenderTiles, BandsCoverEveryRowOnceAndDifferByOneRowAtMost) {
    for (const int height : {1, 7, 37, 360, 2160})
        for (const int count : {1, 2, 3, 16, 17})
            if (count <= height) {
                int next = 0, lo = height, hi = 0;
                for (int i = 1; i <= count; ++i) {
                    int y0 = -1, y1 = -1;
                    tile_rows({i, count}, height, &y0, &y1);
                    EXPECT_EQ(y0, next) << height << " " << i << "/" << count;
                    lo = std::min(lo, y1 - y0);
                    hi = std::max(hi, y1 - y0);
                    next = y1;
                }
                EXPECT_EQ(next, height);
                EXPECT_LE(hi - lo, 1);
                EXPECT_GE(lo, 1);
            }
    int y0 = 0, y1 = 0;
    EXPECT_THROW(tile_rows({1, 8}, 7, &y0, &y1), InputError);
}

TEST(RenderTiles, TilePixelsAreTheBandsRows) {
    // 2 columns × 4 rows × 3 channels, each value its index.
    std::vector<float> px(24);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i);
    const std::vector<float> band = tile_pixels(px, 4, 1, 3);
    ASSERT_EQ(band.size(), 12u);
    EXPECT_EQ(band.front(), 6.0f);
    EXPECT_EQ(band.back(), 17.0f);
}

}  // namespace
}  // namespace pelage::renderer
