// The denoiser against images whose true values are known: a constant, an analytic lit
// plane and a step between two albedos (two cell types), each with independent noise in
// its two halves; its handling of garbage statistics; the bound on what a pixel reads;
// and the same bytes at any thread count.
#include "renderer/denoise/denoise.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

namespace pelage::renderer {
namespace {

struct Truth {
    float colour[3], albedo[3], normal[3], depth;
};

// Two half buffers of a W × H image whose pixel (x, y) truly is truth(x, y): each half's
// colour carries Gaussian noise of standard deviation `sigma` times the value (the noise
// of `samples` samples per half), features are exact.
DenoiseInput noisy_image(int W, int H, float sigma, float samples, uint32_t seed,
                         const std::function<Truth(int, int)> &truth) {
    DenoiseInput in;
    in.width = W;
    in.height = H;
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    const size_t n = size_t(W) * H;
    for (DenoiseHalf &h : in.half) {
        h.colour.resize(3 * n);
        h.albedo.resize(3 * n);
        h.normal.resize(3 * n);
        h.depth.resize(n);
        h.count.assign(n, samples);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                const Truth t = truth(x, y);
                for (int c = 0; c < 3; ++c) {
                    h.colour[3 * i + c] = t.colour[c] * (1 + sigma * gauss(rng));
                    h.albedo[3 * i + c] = t.albedo[c];
                    h.normal[3 * i + c] = t.normal[c];
                }
                h.depth[i] = t.depth;
            }
    }
    return in;
}

std::vector<float> noisy_mean(const DenoiseInput &in) {
    std::vector<float> m(in.half[0].colour.size());
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = 0.5f * (in.half[0].colour[i] + in.half[1].colour[i]);
    return m;
}

double mse(const std::vector<float> &img, int W, int H,
           const std::function<Truth(int, int)> &truth) {
    double s = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = img[3 * (size_t(y) * W + x) + c] - truth(x, y).colour[c];
                s += d * d;
            }
    return s / (3.0 * W * H);
}

Truth constant(int, int) {
    return {{0.4f, 0.3f, 0.2f}, {0.5f, 0.5f, 0.5f}, {0, 0, 1}, 3.0f};
}

TEST(Denoise, AConstantImageConvergesToTheConstant) {
    const int W = 96, H = 64;
    double previous = 1e9;
    for (const float sigma : {0.4f, 0.2f, 0.1f}) {
        const DenoiseInput in = noisy_image(W, H, sigma, 8, 1, constant);
        const std::vector<float> out = denoise(in);
        const double noisy = mse(noisy_mean(in), W, H, constant),
                     clean = mse(out, W, H, constant);
        // A flat image is the denoiser's best case: most of the window is taken in.
        EXPECT_LT(clean * 30, noisy) << sigma;
        EXPECT_LT(clean, previous) << "less noise in, less error out";
        previous = clean;
        double mean = 0;
        for (size_t i = 0; i < out.size(); i += 3) mean += out[i];
        EXPECT_NEAR(mean / (W * H), 0.4, 0.004) << "no bias";
    }
}

// A plane lit by a distant light, seen in perspective: the normal tilts and the depth
// grows along y, the shading albedo · max(0, n·l) varies smoothly.
Truth lit_plane(int x, int y) {
    const float a = 0.2f + 0.6f * float(y) / 80.0f;  // the normal's tilt
    const float n[3] = {0, std::sin(a), std::cos(a)}, l[3] = {0.3f, 0.5f, 0.81f};
    const float shade = std::max(0.0f, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) *
                        (1.0f + 0.002f * float(x));
    Truth t{};
    for (int c = 0; c < 3; ++c) {
        t.albedo[c] = 0.6f - 0.1f * c;
        t.colour[c] = t.albedo[c] * shade;
        t.normal[c] = n[c];
    }
    t.depth = 2.0f + 0.02f * float(y);
    return t;
}

TEST(Denoise, ALitPlaneComesOutCloseToItsAnalyticShading) {
    const int W = 120, H = 80;
    const DenoiseInput in = noisy_image(W, H, 0.3f, 8, 2, lit_plane);
    const std::vector<float> out = denoise(in);
    const double noisy = mse(noisy_mean(in), W, H, lit_plane),
                 clean = mse(out, W, H, lit_plane);
    EXPECT_LT(clean * 10, noisy) << "noisy " << noisy << ", denoised " << clean;
    // The mean of each band of rows keeps its level (a smooth gradient is not bent).
    for (int y0 = 0; y0 < H; y0 += 20) {
        double got = 0, want = 0;
        for (int y = y0; y < y0 + 20; ++y)
            for (int x = 0; x < W; ++x) {
                got += out[3 * (size_t(y) * W + x)];
                want += lit_plane(x, y).colour[0];
            }
        EXPECT_NEAR(got / want, 1.0, 0.01) << "rows " << y0;
    }
}

// Two cell types meeting at column 60: a dark and a light albedo under one shading.
Truth two_types(int x, int) {
    const float a = x < 60 ? 0.05f : 0.6f;
    return {{a * 0.9f, a * 0.8f, a * 0.7f}, {a, a, a}, {0, 0, 1}, 3.0f};
}

TEST(Denoise, AnEdgeBetweenTwoCellTypesStaysWhereItIs) {
    // Tall enough that a column's mean is not its noise: an edge column has only half a
    // window of its own type to average.
    const int W = 120, H = 400;
    const DenoiseInput in = noisy_image(W, H, 0.3f, 8, 3, two_types);
    const std::vector<float> out = denoise(in);
    EXPECT_LT(mse(out, W, H, two_types) * 8, mse(noisy_mean(in), W, H, two_types));
    // Each column's mean against the truth: no column beside the edge bleeds into the
    // other type by more than 2 % (the halo is at most the edge's own pixel).
    for (int x = 0; x < W; ++x) {
        double got = 0;
        for (int y = 0; y < H; ++y) got += out[3 * (size_t(y) * W + x)];
        got /= H;
        const double want = two_types(x, 0).colour[0];
        EXPECT_NEAR(got / want, 1.0, 0.02) << "column " << x;
    }
}

// A plane under a sun and a sky: the sun's light, gathered by the first hit's light
// samples (DenoiseHalf::direct), casts a hard diagonal shadow that no feature holds and
// is nearly noise-free; the sky's light is smooth and noisy. Filtered apart, the noise
// goes and the shadow's edge stays where it is; handed over whole, the filter has to
// choose between the two.
struct SunAndSky {
    float sun, sky;
};
SunAndSky sun_and_sky(int x, int y) {
    return {(x + y / 2) % 40 < 20 ? 0.8f : 0.0f, 0.15f + 0.001f * float(x)};
}
Truth sunlit_plane(int x, int y) {
    const SunAndSky l = sun_and_sky(x, y);
    Truth t{};
    for (int c = 0; c < 3; ++c) {
        t.albedo[c] = 0.6f - 0.1f * c;
        t.colour[c] = t.albedo[c] * (l.sun + l.sky);
    }
    t.normal[2] = 1;
    t.depth = 3.0f;
    return t;
}

TEST(Denoise, TheFirstHitsLightSamplesKeepTheirShadowsSharp) {
    const int W = 120, H = 240;
    DenoiseInput in = noisy_image(W, H, 0.0f, 8, 5, sunlit_plane);
    std::mt19937 rng(6);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (DenoiseHalf &h : in.half) {
        h.direct.resize(h.colour.size());
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                const SunAndSky l = sun_and_sky(x, y);
                for (int c = 0; c < 3; ++c) {
                    const float a = h.albedo[3 * i + c];
                    h.direct[3 * i + c] = a * l.sun * (1 + 0.02f * gauss(rng));
                    h.colour[3 * i + c] =
                        h.direct[3 * i + c] + a * l.sky * (1 + 0.6f * gauss(rng));
                }
            }
    }
    const double noisy = mse(noisy_mean(in), W, H, sunlit_plane);
    const double split = mse(denoise(in), W, H, sunlit_plane);
    EXPECT_LT(split * 10, noisy) << "noisy " << noisy << ", denoised " << split;
    // The same pixels without the split: the shadow's edges cost the filter.
    DenoiseInput whole = in;
    for (DenoiseHalf &h : whole.half) h.direct.clear();
    const double unsplit = mse(denoise(whole), W, H, sunlit_plane);
    EXPECT_LT(split * 2, unsplit) << "whole " << unsplit << ", split " << split;
    // No band along the shadow's edges is off: the lit and shadowed pixels next to an
    // edge keep their levels (rows of 20 pixels either side, within 3 %).
    const std::vector<float> out = denoise(in);
    for (const int side : {0, 1}) {
        double got = 0, want = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 1; x + 1 < W; ++x) {
                const bool lit = sun_and_sky(x, y).sun > 0;
                const bool edge = lit != (sun_and_sky(x - 1, y).sun > 0) ||
                                  lit != (sun_and_sky(x + 1, y).sun > 0);
                if (!edge || lit != bool(side)) continue;
                got += out[3 * (size_t(y) * W + x) + 1];
                want += sunlit_plane(x, y).colour[1];
            }
        EXPECT_NEAR(got / want, 1.0, 0.03) << (side ? "lit" : "shadowed") << " edge";
    }
}

// Garbage in the beauty, the counts and (with the light samples apart, GetParam())
// the direct part: the pixel is kept as the mean of its finite halves and nothing
// spreads to its neighbours.
class DenoiseGarbage : public ::testing::TestWithParam<bool> {};

TEST_P(DenoiseGarbage, IsKeptWhereItIsAndNeverSpreads) {
    const int W = 40, H = 30;
    DenoiseInput in = noisy_image(W, H, 0.2f, 4, 4, constant);
    if (GetParam())
        for (DenoiseHalf &h : in.half) {
            h.direct.resize(h.colour.size());
            for (size_t j = 0; j < h.colour.size(); ++j) h.direct[j] = 0.5f * h.colour[j];
        }
    const std::vector<float> clean = denoise(in);
    const size_t nan_px = 5 * W + 5, inf_px = 20 * W + 30, empty_px = 12 * W + 18,
                 one_half = 25 * W + 8, direct_px = 15 * W + 25;
    in.half[0].colour[3 * nan_px] = std::numeric_limits<float>::quiet_NaN();
    in.half[1].colour[3 * inf_px + 1] = std::numeric_limits<float>::infinity();
    in.half[0].count[empty_px] = in.half[1].count[empty_px] = 0;
    in.half[1].count[one_half] = 0;
    if (GetParam())
        in.half[1].direct[3 * direct_px + 2] = std::numeric_limits<float>::quiet_NaN();
    DenoiseStats stats;
    const std::vector<float> out = denoise(in, {}, &stats);
    EXPECT_EQ(stats.nonfinite_inputs, GetParam() ? 3u : 2u);
    EXPECT_EQ(stats.pixels_passed_through, GetParam() ? 5u : 4u);
    for (const float v : out) ASSERT_TRUE(std::isfinite(v));
    // A pixel with one finite half keeps that half.
    EXPECT_EQ(out[3 * nan_px], in.half[1].colour[3 * nan_px]);
    EXPECT_EQ(out[3 * inf_px + 1], in.half[0].colour[3 * inf_px + 1]);
    EXPECT_EQ(out[3 * empty_px], 0.0f);
    EXPECT_EQ(out[3 * one_half + 2], in.half[0].colour[3 * one_half + 2]);
    if (GetParam())
        EXPECT_EQ(out[3 * direct_px + 2], in.half[0].colour[3 * direct_px + 2]);
    // The others differ from the clean run only as the missing neighbours' weights do:
    // never by a garbage value.
    for (size_t i = 0; i < size_t(W) * H; ++i) {
        if (i == nan_px || i == inf_px || i == empty_px || i == one_half ||
            (GetParam() && i == direct_px))
            continue;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out[3 * i + c], clean[3 * i + c], 0.05f * clean[3 * i + c]) << i;
    }
}

INSTANTIATE_TEST_SUITE_P(Denoise, DenoiseGarbage, ::testing::Bool(),
                         [](const auto &info) {
                             return info.param ? "LightSamplesApart" : "BeautyWhole";
                         });

TEST(Denoise, TinyAndEmptyImagesWork) {
    for (const auto &[W, H] :
         std::vector<std::pair<int, int>>{{1, 1}, {1, 9}, {9, 1}, {0, 0}}) {
        const DenoiseInput in = noisy_image(W, H, 0.2f, 4, 5, constant);
        const std::vector<float> out = denoise(in);
        ASSERT_EQ(out.size(), size_t(3 * W * H));
        for (const float v : out) EXPECT_TRUE(std::isfinite(v));
    }
    // All background: no albedo, no normal, no depth.
    DenoiseInput sky = noisy_image(30, 20, 0.2f, 4, 6, [](int, int) {
        const float inf = std::numeric_limits<float>::infinity();
        return Truth{{0.5f, 0.6f, 0.9f}, {0, 0, 0}, {0, 0, 0}, inf};
    });
    const std::vector<float> out = denoise(sky);
    double mean = 0;
    for (size_t i = 0; i < out.size(); i += 3) mean += out[i];
    EXPECT_NEAR(mean / (30 * 20), 0.5, 0.01);
}

TEST(Denoise, APixelReadsNothingBeyondTheSupportRadius) {
    const int W = 70, H = 50, cx = 35, cy = 25;
    const int r = denoise_support_radius({});
    ASSERT_LT(r, cx);
    const DenoiseInput base = noisy_image(W, H, 0.3f, 4, 7, lit_plane);
    const std::vector<float> ref = denoise(base);
    auto changed = [&](int x, int y) {
        DenoiseInput in = base;
        for (DenoiseHalf &h : in.half) {
            const size_t i = size_t(y) * W + x;
            h.colour[3 * i] *= 3;
            h.albedo[3 * i + 1] = 0.9f;
        }
        const std::vector<float> out = denoise(in);
        const size_t c = 3 * (size_t(cy) * W + cx);
        return out[c] != ref[c] || out[c + 1] != ref[c + 1] || out[c + 2] != ref[c + 2];
    };
    // Just outside, in every direction: the centre's bytes do not move.
    for (const auto &[dx, dy] : std::vector<std::pair<int, int>>{
             {r + 1, 0}, {-r - 1, 0}, {0, r + 1}, {0, -r - 1}, {r + 1, r + 1}})
        EXPECT_FALSE(changed(cx + dx, cy + dy)) << dx << "," << dy;
    // Inside, the centre does move: the bound is not vacuous.
    EXPECT_TRUE(changed(cx + 2, cy + 1));
}

TEST(Denoise, TheSameBytesAtAnyThreadCount) {
    const int W = 150, H = 90;
    const DenoiseInput in = noisy_image(W, H, 0.3f, 4, 8, two_types);
    std::vector<float> one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = denoise(in);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = denoise(in);
    }
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(float)));
}

TEST(Denoise, BuffersOfTheWrongSizeAreRefused) {
    DenoiseInput in = noisy_image(10, 10, 0.1f, 4, 9, constant);
    in.half[1].depth.pop_back();
    EXPECT_THROW(denoise(in), std::invalid_argument);
}

}  // namespace
}  // namespace pelage::renderer
