// Ray cone widening at rough bounces (renderer/core/ray_cone.h): the angle one of spp
// sampled directions stands for; and what it is for, a plugin filtering indirect hits.
#include "renderer/core/ray_cone.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

constexpr float pi = 3.14159265358979f;

TEST(RayCone, CameraConeIsTheSharePerSampleOfThePixel) {
    // 1/√spp of a pixel: a quarter of its area for 4 samples, down to 1/8 of its width.
    EXPECT_EQ(renderer::camera_spread_scale(1), 1.0f);
    EXPECT_EQ(renderer::camera_spread_scale(4), 0.5f);
    EXPECT_NEAR(renderer::camera_spread_scale(2), 1 / std::sqrt(2.0f), 1e-7f);
    EXPECT_EQ(renderer::camera_spread_scale(64), 0.125f);
    EXPECT_EQ(renderer::camera_spread_scale(1 << 20), 0.125f);
    EXPECT_EQ(renderer::camera_spread_scale(0), 1.0f);
}

TEST(RayCone, BounceSpreadIsTheConeOfOneSampledDirection) {
    // A cosine lobe at normal incidence has p = 1/π: one sample per pixel stands for
    // the solid angle π, a cone of full angle 2 (π (θ/2)² = π).
    EXPECT_NEAR(renderer::bounce_spread(1 / pi, 1), 2.0f, 1e-6f);
    // Four times the samples: a quarter of the solid angle, half the angle.
    EXPECT_NEAR(renderer::bounce_spread(1 / pi, 4), 1.0f, 1e-6f);
    // A glossy lobe (p = 100 per steradian) at 16 spp.
    EXPECT_NEAR(renderer::bounce_spread(100, 16), 2 * std::sqrt(1 / (pi * 1600)), 1e-7f);
    // It vanishes as spp grows (consistent filtering) and never exceeds a hemisphere.
    EXPECT_LT(renderer::bounce_spread(1 / pi, 1 << 20), 2e-3f);
    EXPECT_EQ(renderer::bounce_spread(1e-9f, 1), pi);
    EXPECT_EQ(renderer::bounce_spread(0, 4), pi);
    EXPECT_EQ(renderer::bounce_spread(std::nanf(""), 4), pi);
    EXPECT_EQ(renderer::bounce_spread(1, 0), pi);
}

// A white ground lit by a uniform sky and by the light a clonal-mosaic sphere above it
// bounces down; the camera, under the sphere, sees only the ground. The sphere's indirect
// hits come after a diffuse bounce, so their cones are much wider than its triangles, and
// the material's level of detail (lod, on by default) shades them with the cells' mean
// look. That keeps the ground's brightness (the mean look has the pattern's mean albedo)
// and removes the pattern's share of the noise: two renders with different seeds differ
// less (by 25 % in variance here). A small ground under a large sphere: the sphere's
// underside is lit evenly from below, so the pattern is a large part of the noise.
std::string bounce_scene(const std::string &cells, int lod) {
    return R"({
      "camera": {"position": [0, -0.8, 0], "look_at": [0, -1, 0], "up": [0, 0, 1], "fov": 60},
      "film": {"width": 64, "height": 64, "spp": 4, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 0.5}],
      "objects": [{"mesh": "procedural:icosphere:3", "cells": ")" +
           cells + R"(",
                   "transform": {"scale": 3, "translate": [0, 2.3, 0]},
                   "material": {"shader": "clonal_mosaic", "params": {"lod": )" +
           std::to_string(lod) + R"(}}},
                  {"mesh": "procedural:plane:1x1", "transform": {"scale": 0.4, "translate": [0, -1, 0]},
                   "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
      "integrator": {"max_depth": 2, "rr_depth": 8}
    })";
}

TEST(RayCone, IndirectHitsOfAPatternAreFilteredWithoutChangingTheMean) {
    TempDir tmp;
    // Colours 0.1 and 0.9 in red: a strongly varying albedo.
    const std::string cells = simulate_two_type_cells(tmp, "procedural:icosphere:3", 600);
    double mean[2] = {0, 0}, noise[2] = {0, 0};
    for (int lod = 0; lod < 2; ++lod) {
        const RenderedImage a = render_json(bounce_scene(cells, lod), tmp, 0, 1);
        const RenderedImage b = render_json(bounce_scene(cells, lod), tmp, 0, 2);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                mean[lod] += (a.at(x, y, 0) + b.at(x, y, 0)) / (2 * 64 * 64);
                const double d = a.at(x, y, 0) - b.at(x, y, 0);
                noise[lod] += d * d / (64 * 64);
            }
    }
    ASSERT_GT(mean[0], 0.05);
    // The filter is local (about two triangles): the few dozen cells this ground sees
    // are averaged with their neighbours', which moves the mean by about 2 % here.
    EXPECT_NEAR(mean[1], mean[0], 0.05 * mean[0])
        << "lod changed the brightness " << mean[1] << " " << noise[1] << " vs "
        << noise[0];
    EXPECT_LT(noise[1], 0.9 * noise[0]) << "lod " << noise[1] << " exact " << noise[0];
}

}  // namespace
}  // namespace pelage::test
