// The samplers' polynomial sine and cosine, the warps built on them, and light
// selection by alias table: each checked against an exact reference.
#include "renderer/core/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "renderer/core/sin_cos.h"
#include "renderer/lights/lights.h"

namespace pelage::test {
namespace {

TEST(SinCos, QuarterTurnPolynomialsMatchDoublePrecision) {
    const double quarter = M_PI / 4;
    double worst = 0;
    for (int k = -100000; k <= 100000; ++k) {
        const float x = float(quarter * k / 100000);
        float s, c;
        renderer::sin_cos_quarter(x, &s, &c);
        worst = std::max({worst, std::abs(s - std::sin(double(x))),
                          std::abs(c - std::cos(double(x)))});
    }
    EXPECT_LT(worst, 2e-7);
}

TEST(SinCos, FullTurnMatchesDoublePrecisionInEveryOctant) {
    double worst = 0;
    for (int k = 0; k <= 1 << 20; ++k) {
        const float u = float(k) / float(1 << 20);  // includes 0, 1/8, …, 1
        float s, c;
        renderer::sin_cos_turn(u, &s, &c);
        const double phi = 2 * M_PI * double(u);
        worst =
            std::max({worst, std::abs(s - std::sin(phi)), std::abs(c - std::cos(phi))});
    }
    EXPECT_LT(worst, 3e-7);
    float s, c;
    renderer::sin_cos_turn(0.25f, &s, &c);  // exact quarter turns stay exact
    EXPECT_EQ(s, 1.0f);
    EXPECT_EQ(c, 0.0f);
    renderer::sin_cos_turn(0.5f, &s, &c);
    EXPECT_EQ(c, -1.0f);
}

TEST(SampleDisk, ConcentricMapMatchesTheClosedFormAndFillsTheDisk) {
    // Shirley & Chiu's map with libm's sin and cos in double as the reference; the four
    // quadrants of the disk each receive a quarter of a uniform grid of u.
    int quadrant[4] = {0, 0, 0, 0};
    double worst = 0;
    constexpr int n = 512;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float u1 = (i + 0.5f) / n, u2 = (j + 0.5f) / n;
            float x, y;
            renderer::sample_disk(u1, u2, &x, &y);
            const double a = 2.0 * u1 - 1, b = 2.0 * u2 - 1;
            const double r = std::abs(a) > std::abs(b) ? a : b;
            const double phi = std::abs(a) > std::abs(b) ? M_PI / 4 * (b / a)
                                                         : M_PI / 2 - M_PI / 4 * (a / b);
            worst = std::max({worst, std::abs(x - r * std::cos(phi)),
                              std::abs(y - r * std::sin(phi))});
            ASSERT_LE(x * x + y * y, 1.0f + 1e-6f);
            ++quadrant[(x >= 0 ? 0 : 1) + (y >= 0 ? 0 : 2)];
        }
    EXPECT_LT(worst, 3e-7);
    for (int q : quadrant) EXPECT_EQ(q, n * n / 4);
}

TEST(SampleCone, DirectionsStayInTheConeAndAreUnit) {
    const float cos_max = std::cos(0.2f);
    for (int k = 0; k < 4096; ++k) {
        const Vec3f w = renderer::sample_uniform_cone((k % 64 + 0.5f) / 64,
                                                      (k / 64 + 0.5f) / 64, cos_max);
        EXPECT_NEAR(length(w), 1.0f, 1e-6f);
        EXPECT_GE(w.z, cos_max - 1e-6f);
    }
}

TEST(SampleCosineHemisphere, UnitDirectionsWithTheMomentsOfCosThetaOverPi) {
    // For density cos θ / π: E[cos θ] = 2/3, E[cos² θ] = 1/2, E[x] = E[y] = 0, and the
    // fraction within θ < 60° is 1 − cos² 60° = 3/4. A 1024² grid of u: errors ~1e-6.
    constexpr int n = 1024;
    double z1 = 0, z2 = 0, x1 = 0, y1 = 0, inside = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Vec3f w =
                renderer::sample_cosine_hemisphere((i + 0.5f) / n, (j + 0.5f) / n);
            ASSERT_NEAR(length(w), 1.0f, 1e-6f);
            ASSERT_GE(w.z, 0.0f);
            z1 += w.z;
            z2 += w.z * w.z;
            x1 += w.x;
            y1 += w.y;
            inside += w.z > 0.5f;
        }
    const double m = double(n) * n;
    EXPECT_NEAR(z1 / m, 2.0 / 3, 1e-4);
    EXPECT_NEAR(z2 / m, 0.5, 1e-4);
    EXPECT_NEAR(x1 / m, 0.0, 1e-4);
    EXPECT_NEAR(y1 / m, 0.0, 1e-4);
    EXPECT_NEAR(inside / m, 0.75, 1e-3);
}

// Light selection: the fraction of a fine grid of u that picks each light is its
// select_pdf, for lights of very different power, including one that emits nothing.
TEST(LightSelection, AliasTablePicksEachLightWithItsProbability) {
    std::vector<renderer::LightDesc> descs;
    for (float intensity : {1.0f, 40.0f, 0.0f, 3.0f, 0.25f, 7.0f, 1.0f}) {
        renderer::LightDesc d;
        d.type = renderer::LightDesc::Type::sphere;
        d.radius = 0.5f;
        d.intensity = intensity;
        descs.push_back(d);
    }
    for (auto selection : {renderer::IntegratorDesc::LightSelection::power,
                           renderer::IntegratorDesc::LightSelection::uniform}) {
        const renderer::Lights lights(descs, 10.0f, selection);
        const int m = lights.count();
        constexpr int n = 1 << 20;
        std::vector<int> picked(m, 0);
        for (int k = 0; k < n; ++k) {
            float pdf;
            const int i = lights.select((k + 0.5f) / n, &pdf);
            ASSERT_GE(i, 0);
            ASSERT_LT(i, m);
            ASSERT_EQ(pdf, lights.select_pdf(i));
            ++picked[i];
        }
        double total_pdf = 0;
        for (int i = 0; i < m; ++i) {
            total_pdf += lights.select_pdf(i);
            EXPECT_NEAR(double(picked[i]) / n, lights.select_pdf(i), 1e-4) << i;
        }
        EXPECT_NEAR(total_pdf, 1.0, 1e-6);
        if (selection == renderer::IntegratorDesc::LightSelection::power) {
            EXPECT_EQ(picked[2], 0);  // intensity 0: never chosen
            EXPECT_NEAR(lights.select_pdf(1) / lights.select_pdf(0), 40.0, 1e-3);
        } else {
            EXPECT_EQ(lights.select_pdf(2), 1.0f / 7);
        }
    }
}

}  // namespace
}  // namespace pelage::test
