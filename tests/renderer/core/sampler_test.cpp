// The Sobol sampler's defining property, checked by counting: a pixel's first 2^k
// samples form a (0, 2)-net in every dimension pair (each elementary interval of area
// 2^-k holds exactly one point) and are stratified in every 1D dimension; pairs are
// scrambled independently of each other.
#include "renderer/core/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pelage::renderer {
namespace {

// The points of `n` samples of pixel (x, y) in dimension pair `pair`.
std::vector<Sampler::Pair> pair_points(Sampler s, int n, int pair, uint32_t x = 3,
                                       uint32_t y = 7) {
    std::vector<Sampler::Pair> p;
    for (int i = 0; i < n; ++i) {
        s.start_pixel_sample(x, y, uint32_t(i));
        for (int d = 0; d < pair; ++d) s.get_2d();
        p.push_back(s.get_2d());
    }
    return p;
}

// True when every elementary interval [a 2^-i, (a+1) 2^-i) × [b 2^-j, (b+1) 2^-j) with
// i + j = log2(n) holds exactly one point.
bool is_02_net(const std::vector<Sampler::Pair> &p) {
    const int n = int(p.size());
    const int m = int(std::log2(n));
    for (int i = 0; i <= m; ++i) {
        const int cols = 1 << i, rows = 1 << (m - i);
        std::vector<int> count(size_t(n), 0);
        for (const auto &q : p)
            ++count[size_t(int(q.u2 * rows) * cols + int(q.u1 * cols))];
        for (int c : count)
            if (c != 1) return false;
    }
    return true;
}

TEST(Sampler, EveryPairOfAPixelIsA02NetAtEveryPowerOfTwo) {
    const Sampler s(5, 2);
    for (int pair = 0; pair < 8; ++pair)
        for (int n : {1, 2, 4, 16, 64, 256}) {
            const std::vector<Sampler::Pair> p = pair_points(s, n, pair);
            EXPECT_TRUE(is_02_net(p)) << "pair " << pair << ", " << n << " samples";
            for (const auto &q : p) {
                ASSERT_GE(q.u1, 0.0f);
                ASSERT_LT(q.u1, 1.0f);
                ASSERT_GE(q.u2, 0.0f);
                ASSERT_LT(q.u2, 1.0f);
            }
        }
}

TEST(Sampler, OneDimensionalSamplesAreStratified) {
    Sampler s(9, 0);
    constexpr int n = 128;
    for (int dim = 0; dim < 6; ++dim) {
        std::vector<int> count(n, 0);
        for (int i = 0; i < n; ++i) {
            s.start_pixel_sample(1, 2, uint32_t(i));
            for (int d = 0; d < dim; ++d) s.get_1d();
            ++count[size_t(s.get_1d() * n)];
        }
        for (int c : count) ASSERT_EQ(c, 1) << "dimension " << dim;
    }
}

TEST(Sampler, PairsAndPixelsAreScrambledIndependently) {
    const Sampler s(5, 2);
    // Another pair of the same pixel, or the same pair of another pixel or frame, is
    // another net: not the same points, and the u1 of two pairs do not correlate.
    const auto a = pair_points(s, 256, 0), b = pair_points(s, 256, 1);
    const auto c = pair_points(s, 256, 0, 4, 7), d = pair_points(Sampler(5, 3), 256, 0);
    double sab = 0, sa = 0, sb = 0, saa = 0, sbb = 0;
    int same_b = 0, same_c = 0, same_d = 0;
    for (int i = 0; i < 256; ++i) {
        sab += a[i].u1 * b[i].u1, sa += a[i].u1, sb += b[i].u1;
        saa += a[i].u1 * a[i].u1, sbb += b[i].u1 * b[i].u1;
        same_b += a[i].u1 == b[i].u1;
        same_c += a[i].u1 == c[i].u1;
        same_d += a[i].u1 == d[i].u1;
    }
    const double n = 256, cov = sab / n - sa * sb / (n * n);
    const double r =
        cov / std::sqrt((saa / n - sa * sa / (n * n)) * (sbb / n - sb * sb / (n * n)));
    EXPECT_LT(std::abs(r), 0.2);
    EXPECT_LT(same_b + same_c + same_d, 3);
}

TEST(Sampler, IndependentKindIsWhiteNoise) {
    // The comparison sampler is not stratified: 64 points of one pair are (almost
    // surely) not a (0, 2)-net.
    const Sampler s(5, 2, Sampler::Kind::independent);
    EXPECT_FALSE(is_02_net(pair_points(s, 64, 0)));
}

}  // namespace
}  // namespace pelage::renderer
