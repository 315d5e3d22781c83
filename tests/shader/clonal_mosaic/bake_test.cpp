// `pelage bake`'s atlas: undistorted (each face keeps its shape), disjoint, and the baked
// texels equal the renderer's lookup — exactly at texel centres, and through the UVs at
// random surface points up to texel-size discretisation.
#include "shader/clonal_mosaic/bake.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(Bake, AtlasTrianglesAreUndistortedCopiesOfTheFaces) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const shader::clonal_mosaic::MosaicPattern pattern(
        simulate_two_type_cells(tmp, mesh, 500, 0.4), mesh);
    const shader::clonal_mosaic::Atlas atlas =
        shader::clonal_mosaic::pack_atlas(pattern.surface().crps, 1024);
    for (sim::TriId t = 0; t < pattern.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const double l3 = length(pattern.surface().mesh.vertex(t, (c + 1) % 3) -
                                     pattern.surface().mesh.vertex(t, c));
            const double la = length(atlas.triangles[t].corners[(c + 1) % 3] -
                                     atlas.triangles[t].corners[c]);
            ASSERT_NEAR(la, l3 * atlas.texels_per_unit, 1e-6 * la);
            ASSERT_GE(atlas.triangles[t].corners[c].x, 0.0);
            ASSERT_LE(atlas.triangles[t].corners[c].y, 1024.0);
        }
}

TEST(Bake, TexelsEqualTheRenderersLookup) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const shader::clonal_mosaic::MosaicPattern pattern(
        simulate_two_type_cells(tmp, mesh, 500, 0.4), mesh);
    const int res = 512;
    const shader::clonal_mosaic::BakedPattern baked =
        shader::clonal_mosaic::bake_pattern(pattern, res);
    const auto id_at = [&](int x, int y) {
        return baked.pixels[(size_t(y) * res + x) *
                                shader::clonal_mosaic::BakedPattern::channels +
                            5];
    };

    // Exactly at the centres of texels inside a triangle.
    size_t centres = 0;
    for (sim::TriId t = 0; t < pattern.num_triangles(); t += 3) {
        const auto &a = baked.atlas.triangles[t];
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                const sim::Vec2d p{x + 0.5, y + 0.5}, e1 = a.corners[1] - a.corners[0],
                                                      e2 = a.corners[2] - a.corners[0];
                const double det = cross(e1, e2), b1 = cross(p - a.corners[0], e2) / det,
                             b2 = cross(e1, p - a.corners[0]) / det;
                if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
                const shader::clonal_mosaic::ClosestCell c = pattern.index().find_nearest(
                    t, pattern.point(t, float(b1), float(b2)));
                ASSERT_EQ(id_at(x, y), float(pattern.cells().id[c.index]));
                ++centres;
            }
    }
    EXPECT_GT(centres, 5000u);

    // Through the UVs (what the texture plugin does) at random surface points.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    size_t agree = 0, n = 20000;
    for (size_t i = 0; i < n; ++i) {
        const sim::TriId t = rng() % pattern.num_triangles();
        float b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        sim::Vec2d uv{0, 0};
        const float b[3] = {1 - b1 - b2, b1, b2};
        for (int c = 0; c < 3; ++c) uv += baked.atlas.uv(t, c) * b[c];
        const int x = std::min(res - 1, int(uv.x * res)),
                  y = std::min(res - 1, int((1 - uv.y) * res));
        const shader::clonal_mosaic::ClosestCell c =
            pattern.index().find_nearest(t, pattern.point(t, b1, b2));
        agree += id_at(x, y) == float(pattern.cells().id[c.index]);
    }
    // Disagreement only within a texel of a cell edge: a few percent at this resolution.
    EXPECT_GT(double(agree) / n, 0.95);
}

}  // namespace
}  // namespace pelage::test
