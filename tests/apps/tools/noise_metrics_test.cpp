#include "apps/tools/noise_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pelage::renderer {
namespace {

constexpr int W = 8, H = 6, S = 4;

// A reference of constant value v covering columns [x0, W) (alpha 1), empty elsewhere.
std::vector<float> covered(float v, int x0) {
    std::vector<float> p(size_t(W) * H * S, 0.0f);
    for (int y = 0; y < H; ++y)
        for (int x = x0; x < W; ++x)
            for (int c = 0; c < 4; ++c) p[(size_t(y) * W + x) * S + c] = c < 3 ? v : 1;
    return p;
}

TEST(NoiseMetrics, MseCountsObjectPixelsAndChannelsOnly) {
    const std::vector<float> ref = covered(0.5f, 2);
    std::vector<float> img = ref;
    // Background pixels differ wildly: not measured.
    img[0] = 100;
    // One object pixel's red channel is off by 0.3: MSE = 0.09 / (3 · 36).
    img[(size_t(1) * W + 4) * S + 0] += 0.3f;
    const NoiseMetrics m = measure_noise(img, ref, W, H, S);
    EXPECT_EQ(m.pixels, size_t(6 * H));
    EXPECT_NEAR(m.mse, 0.09 / (3.0 * 36), 1e-8);  // 0.3 in float
    EXPECT_NEAR(m.rmse, std::sqrt(0.09 / (3.0 * 36)), 1e-7);
    EXPECT_FLOAT_EQ(m.reference_max, 0.5f);
    EXPECT_NEAR(m.reference_mean, 0.5, 1e-7);
    // The image's red is 0.3 brighter on one of 36 object pixels; the background's 100
    // does not count.
    EXPECT_NEAR(m.mean_rgb[0], 0.5 + 0.3 / 36, 1e-7);
    EXPECT_NEAR(m.mean_rgb[1], 0.5, 1e-7);
    EXPECT_NEAR(m.reference_mean_rgb[0], 0.5, 1e-7);
    // The worst object pixel is 0.3 off, 0.6 of the mean; the background's 100 is not.
    EXPECT_NEAR(m.max_error, 0.3, 1e-6);
    EXPECT_NEAR(m.max_error_over_mean(), 0.6, 2e-6);
}

TEST(NoiseMetrics, AnIsolatedSpikeIsNoFireflyAClusterIs) {
    const std::vector<float> ref = covered(0.5f, 0);
    std::vector<float> img = ref;
    img[(size_t(2) * W + 2) * S + 1] = 50;  // one pixel: the median removes it
    EXPECT_EQ(measure_noise(img, ref, W, H, S).fireflies, 0u);
    // A 2×3 block above the reference's maximum survives a 3×3 median at the pixels
    // where it holds the majority of the window.
    for (int y = 2; y <= 4; ++y)
        for (int x = 5; x <= 6; ++x) img[(size_t(y) * W + x) * S + 2] = 9;
    const NoiseMetrics m = measure_noise(img, ref, W, H, S);
    EXPECT_GE(m.fireflies, 2u);
    EXPECT_FLOAT_EQ(m.median_max, 9.0f);
}

TEST(NoiseMetrics, MedianOfAKnownWindow) {
    std::vector<float> p(size_t(3) * 3 * S, 0.0f);
    for (int i = 0; i < 9; ++i) p[size_t(i) * S] = float(9 - i);  // 9..1
    const std::vector<float> med = median3x3(p, 3, 3, S, 0);
    EXPECT_FLOAT_EQ(med[4], 5.0f);  // the centre sees all nine values
}

TEST(NoiseMetrics, RefusesMismatchedSizes) {
    EXPECT_THROW(measure_noise(covered(1, 0), std::vector<float>(4), W, H, S),
                 std::invalid_argument);
}

}  // namespace
}  // namespace pelage::renderer
