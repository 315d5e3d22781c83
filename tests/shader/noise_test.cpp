// The Worley and Perlin baselines: analytic properties and brute-force references.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shader/perlin/perlin_noise.h"
#include "shader/worley/worley_noise.h"

namespace pelage::shader {
namespace {

using perlin::PerlinNoise;
using worley::worley_cube_points;
using worley::WorleyResult;

TEST(PerlinNoise, ZeroAtLatticePointsAndBounded) {
    const PerlinNoise n(7);
    for (int x = -3; x <= 3; ++x)
        for (int y = -3; y <= 3; ++y) EXPECT_EQ(n.noise(float(x), float(y), 2.0f), 0.0f);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-50, 50);
    double sum = 0;
    const int count = 200000;
    for (int i = 0; i < count; ++i) {
        const float v = n.noise(u(rng), u(rng), u(rng));
        ASSERT_LE(std::abs(v), 1.0f);
        sum += v;
    }
    EXPECT_LT(std::abs(sum / count), 0.01);  // zero mean: gradients are symmetric
}

TEST(PerlinNoise, ContinuousAndSeedDependent) {
    const PerlinNoise a(1), b(2);
    // The quintic fade makes noise C2; a small step makes a small change.
    for (float x = 0.05f; x < 5; x += 0.37f) {
        const float d = std::abs(a.noise(x, 0.3f, 0.7f) - a.noise(x + 1e-3f, 0.3f, 0.7f));
        EXPECT_LT(d, 1e-2f);
    }
    int differ = 0;
    for (float x = 0.5f; x < 20; x += 1.1f)
        differ += a.noise(x, 0.5f, 0.5f) != b.noise(x, 0.5f, 0.5f);
    EXPECT_GT(differ, 10);
    EXPECT_EQ(a.fbm(1.3f, 2.1f, 0.2f, 5, 2.0f, 0.5f),
              PerlinNoise(1).fbm(1.3f, 2.1f, 0.2f, 5, 2.0f, 0.5f));
}

// Brute force over every feature point of a 9x9x9 block of cubes around the query.
// Worley 1996: F1 is 0 at a feature point (whose id it reports), and F1 <= F2 everywhere.
TEST(WorleyNoise, F1IsZeroAtFeaturePointsAndNeverAboveF2) {
    size_t points = 0;
    for (int32_t x = -3; x <= 3; ++x)
        for (int32_t z = -3; z <= 3; ++z) {
            float pts[16][3];
            uint32_t ids[16];
            const int n = worley_cube_points(x, 1, z, 5, 3.0f, pts, ids);
            for (int i = 0; i < n; ++i, ++points) {
                const WorleyResult r = worley::worley(pts[i], 5, 3.0f);
                ASSERT_LT(r.f1, 1e-6f);
                ASSERT_EQ(r.id1, ids[i]);
                ASSERT_GT(r.f2, 0.0f);
            }
        }
    EXPECT_GT(points, 50u);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-50, 50);
    for (int s = 0; s < 20000; ++s) {
        const float p[3] = {u(rng), u(rng), u(rng)};
        const WorleyResult r = worley::worley(p, 5, 3.0f);
        ASSERT_LE(r.f1, r.f2);
    }
}

TEST(WorleyNoise, F1AndF2MatchBruteForce) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-20, 20);
    for (int s = 0; s < 300; ++s) {
        const float p[3] = {u(rng), u(rng), u(rng)};
        const WorleyResult r =
            worley::worley(p, 9, 1.0f);  // sparse: exercises the outer rings
        double d1 = 1e30, d2 = 1e30;
        uint32_t id1 = 0;
        for (int dx = -4; dx <= 4; ++dx)
            for (int dy = -4; dy <= 4; ++dy)
                for (int dz = -4; dz <= 4; ++dz) {
                    float pts[16][3];
                    uint32_t ids[16];
                    const int n = worley_cube_points(
                        int(std::floor(p[0])) + dx, int(std::floor(p[1])) + dy,
                        int(std::floor(p[2])) + dz, 9, 1.0f, pts, ids);
                    for (int i = 0; i < n; ++i) {
                        const double d = std::hypot(pts[i][0] - p[0], pts[i][1] - p[1],
                                                    pts[i][2] - p[2]);
                        if (d < d1) {
                            d2 = d1;
                            d1 = d;
                            id1 = ids[i];
                        } else if (d < d2) {
                            d2 = d;
                        }
                    }
                }
        ASSERT_NEAR(r.f1, d1, 1e-5);
        ASSERT_NEAR(r.f2, d2, 1e-5);
        ASSERT_EQ(r.id1, id1);
    }
}

TEST(WorleyNoise, DensityFollowsThePoissonMean) {
    // Mean F1 for a Poisson process of density λ is Γ(4/3)/(4πλ/3)^(1/3) ≈ 0.554
    // λ^(-1/3).
    for (float lambda : {1.0f, 3.0f}) {
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> u(-100, 100);
        double sum = 0;
        const int count = 40000;
        for (int i = 0; i < count; ++i) {
            const float p[3] = {u(rng), u(rng), u(rng)};
            sum += worley::worley(p, 3, lambda).f1;
        }
        const double expected = 0.8929795 / std::cbrt(4.0 * M_PI * lambda / 3.0);
        EXPECT_NEAR(sum / count, expected, 0.03 * expected) << lambda;
    }
}

}  // namespace
}  // namespace pelage::shader
