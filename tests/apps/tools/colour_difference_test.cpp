// CIE L*a*b* of linear sRGB against published values: the sRGB primaries and white under
// D65 as tabulated by B. Lindbloom's calculator (brucelindbloom.com, sRGB, D65, no
// adaptation): red (53.2408, 80.0925, 67.2032), green (87.7347, -86.1827, 83.1793),
// blue (32.2970, 79.1875, -107.8602); and the linear branch of f near black.
#include "apps/tools/colour_difference.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pelage::renderer {
namespace {

void expect_lab(const Rgb &rgb, double l, double a, double b) {
    const auto lab = cie_lab(rgb);
    EXPECT_NEAR(lab[0], l, 0.01);
    EXPECT_NEAR(lab[1], a, 0.02);
    EXPECT_NEAR(lab[2], b, 0.02);
}

TEST(ColourDifference, LabOfTheSrgbPrimariesIsThePublishedOne) {
    expect_lab({1, 1, 1}, 100, 0, 0);
    expect_lab({0.5f, 0.5f, 0.5f}, 116 * std::cbrt(0.5) - 16, 0, 0);
    expect_lab({1, 0, 0}, 53.2408, 80.0925, 67.2032);
    expect_lab({0, 1, 0}, 87.7347, -86.1827, 83.1793);
    expect_lab({0, 0, 1}, 32.2970, 79.1875, -107.8602);
    // Below (6/29)^3 L* is linear in Y: 903.3 Y (CIE 15:2004 Eq. 8.1's other branch).
    expect_lab({0.001f, 0.001f, 0.001f}, 0.001 * 24389.0 / 27.0, 0, 0);
}

TEST(ColourDifference, DeltaEIsTheLabDistance) {
    EXPECT_DOUBLE_EQ(delta_e76({0.2f, 0.3f, 0.4f}, {0.2f, 0.3f, 0.4f}), 0);
    // Greys differ in L* only.
    EXPECT_NEAR(delta_e76({1, 1, 1}, {0.5f, 0.5f, 0.5f}), 116 - 116 * std::cbrt(0.5),
                1e-6);
    const Rgb a{0.62f, 0.36f, 0.11f}, b{0.0116f, 0.0097f, 0.008f};
    const auto p = cie_lab(a), q = cie_lab(b);
    EXPECT_NEAR(delta_e76(a, b), std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]), 1e-9);
    EXPECT_DOUBLE_EQ(delta_e76(a, b), delta_e76(b, a));
}

}  // namespace
}  // namespace pelage::renderer
