// A plugin's coat overrides reach the BSDF: the clonal mosaic's per-type `specular` (an
// ior per cell type) renders like the material's own ior when they agree, and differently
// when they do not.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

std::string coated_sphere(const std::string &cells, float ior,
                          const std::string &specular) {
    return R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 32, "height": 32, "spp": 16, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 0.3},
                 {"type": "distant", "direction": [-0.3, -0.4, -1], "angle": 2, "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:3", "cells": ")" +
           cells + R"(", "material": {"shader": "clonal_mosaic",
                   "params": {"specular": ")" +
           specular + R"("}, "bsdf": "coated", "roughness": 0.2, "ior": )" +
           std::to_string(ior) + R"(}}],
      "integrator": {"max_depth": 3, "rr_depth": 8}
    })";
}

// Mean |a - b| over the beauty channels, and the mean of a.
void compare(const RenderedImage &a, const RenderedImage &b, double *diff, double *mean) {
    *diff = *mean = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                *diff += std::abs(a.at(x, y, c) - b.at(x, y, c));
                *mean += a.at(x, y, c);
            }
    const double n = 3.0 * a.width * a.height;
    *diff /= n;
    *mean /= n;
}

TEST(CoatOverride, PerTypeSpecularRendersAsTheMaterialsIor) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, "procedural:icosphere:3", 600);
    const RenderedImage own = render_json(coated_sphere(cells, 1.5f, ""), tmp);
    // The material says 1.2; the plugin overrides it with F0 0.04, i.e. 1.5, everywhere.
    const RenderedImage overridden =
        render_json(coated_sphere(cells, 1.2f, "F=0.04,B=0.04"), tmp);
    const RenderedImage plain = render_json(coated_sphere(cells, 1.2f, ""), tmp);
    const RenderedImage glossy =
        render_json(coated_sphere(cells, 1.5f, "F=0.25,B=0.25"), tmp);
    double diff, mean;
    compare(own, overridden, &diff, &mean);
    ASSERT_GT(mean, 0.01);
    // Same ior, same samples: only F̄_int's table (2e-5) and rounding differ.
    EXPECT_LT(diff, 1e-3 * mean);
    compare(own, plain, &diff, &mean);
    EXPECT_GT(diff, 1e-2 * mean);  // without the override the 1.2 coat shows
    compare(own, glossy, &diff, &mean);
    EXPECT_GT(diff, 5e-2 * mean);  // an ior-3 coat is much glossier
}

}  // namespace
}  // namespace pelage::test
