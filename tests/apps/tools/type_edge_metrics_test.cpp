// The edge metrics against images whose halo and bias are known by construction: a
// step between two cell types, blurred by a box of known width, scaled by a known
// factor, or untouched.
#include "apps/tools/type_edge_metrics.h"

#include <gtest/gtest.h>

namespace pelage::renderer {
namespace {

constexpr int W = 120, H = 80, stride = 4;
// A band along the edge is one column of H pixels per side and distance.
constexpr size_t min_pixels = 50;

// Type 0 (value 0.2) left of column 60, type 1 (value 0.8) right of it.
std::vector<float> types() {
    std::vector<float> t(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) t[size_t(y) * W + x] = x < 60 ? 0.0f : 1.0f;
    return t;
}
std::vector<float> step_image() {
    std::vector<float> img(size_t(W) * H * stride, 1.0f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c)
                img[(size_t(y) * W + x) * stride + c] = x < 60 ? 0.2f : 0.8f;
    return img;
}
// A horizontal box blur of radius r.
std::vector<float> blurred(const std::vector<float> &img, int r) {
    std::vector<float> out = img;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                double s = 0;
                int n = 0;
                for (int d = -r; d <= r; ++d)
                    if (x + d >= 0 && x + d < W) {
                        s += img[(size_t(y) * W + x + d) * stride + c];
                        ++n;
                    }
                out[(size_t(y) * W + x) * stride + c] = float(s / n);
            }
    return out;
}

TEST(TypeEdgeMetrics, TheReferenceItselfHasNoHaloAndNoBias) {
    const auto ref = step_image();
    const TypeEdgeMetrics m =
        measure_type_edges(ref, ref, types(), W, H, stride, 4, 8, 0.02, min_pixels);
    EXPECT_EQ(m.halo_pixels, 0);
    EXPECT_EQ(m.max_bias, 0.0);
    ASSERT_EQ(m.types.size(), 2u);
}

TEST(TypeEdgeMetrics, ABlurOfRadiusRLeavesAHaloOfRPixels) {
    const auto ref = step_image();
    for (const int r : {2, 4}) {
        // A pixel at distance d from the edge pixels (both columns 59 and 60 are at 0)
        // sees the other side when d < r: the last such band is d = r − 1.
        const TypeEdgeMetrics m = measure_type_edges(blurred(ref, r), ref, types(), W, H,
                                                     stride, 6, 8, 0.02, min_pixels);
        EXPECT_EQ(m.halo_pixels, r - 1) << r;
        EXPECT_EQ(m.max_bias, 0.0) << "the interior (6 px and more) is untouched";
    }
}

TEST(TypeEdgeMetrics, AScaledTypeIsItsBias) {
    const auto ref = step_image();
    auto img = ref;
    for (size_t i = 0; i < size_t(W) * H; ++i)
        if (i % W < 60)
            for (int c = 0; c < 3; ++c) img[i * stride + c] *= 1.05f;
    const TypeEdgeMetrics m =
        measure_type_edges(img, ref, types(), W, H, stride, 4, 8, 0.02, min_pixels);
    EXPECT_NEAR(m.max_bias, 0.05, 1e-5);
    EXPECT_NEAR(m.types[0].bias, 0.05, 1e-5);
    EXPECT_NEAR(m.types[1].bias, 0.0, 1e-6);
    // A 5 % error everywhere on type 0 is a band at every distance: the widest measured.
    EXPECT_EQ(m.halo_pixels, 8);
}

}  // namespace
}  // namespace pelage::renderer
