// `pelage bake`: the atlas is undistorted (each face keeps its shape), its triangles do
// not overlap and it covers >= 70 % of the texels on the cow; a texel's colour is the
// clonal_mosaic shader's own filtered look at its surface point for its footprint (the
// plugin called through its ABI), its ids those of the nearest cell; no texel within the
// gutter of a chart stays uncovered; UVs over several UDIM tiles bake into those tiles,
// and UVs outside 1001-1100 are refused.
#include "pattern/bake/bake.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "pattern/transfer/surface_transfer.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/crps/surface.h"
#include "tests/shader/clonal_mosaic/mosaic_plugin_instance.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace cm = pattern::bake;
const std::string mesh_spec = "procedural:icosphere:3";

// Barycentrics of q in triangle p.
sim::Vec3d barycentric(const std::array<sim::Vec2d, 3> &p, sim::Vec2d q) {
    const sim::Vec2d e1 = p[1] - p[0], e2 = p[2] - p[0], r = q - p[0];
    const double det = cross(e1, e2), b1 = cross(r, e2) / det, b2 = cross(e1, r) / det;
    return {1 - b1 - b2, b1, b2};
}

double distance_to(const std::array<sim::Vec2d, 3> &p, sim::Vec2d q) {
    const sim::Vec3d b = barycentric(p, q);
    if (b.x >= 0 && b.y >= 0 && b.z >= 0) return 0;
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
        const sim::Vec2d a = p[k], ab = p[(k + 1) % 3] - a;
        const double t = std::clamp(dot(q - a, ab) / dot(ab, ab), 0.0, 1.0);
        best = std::min(best, length(q - (a + ab * t)));
    }
    return best;
}

TEST(Bake, AtlasTrianglesAreUndistortedAndDisjoint) {
    const sim::Surface s = sim::build_surface(mesh_spec);
    const cm::Atlas atlas = cm::pack_atlas(s.crps, 1024, 512);
    ASSERT_GT(atlas.texels_per_unit, 0);
    const size_t nt = s.mesh.num_triangles();
    for (sim::TriId t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c) {
            const double l3 = length(s.mesh.vertex(t, (c + 1) % 3) - s.mesh.vertex(t, c));
            const double la = length(atlas.corners[t][(c + 1) % 3] - atlas.corners[t][c]);
            ASSERT_NEAR(la, l3 * atlas.texels_per_unit, 1e-6 * la);
            ASSERT_GE(atlas.corners[t][c].x, 0.0);
            ASSERT_LE(atlas.corners[t][c].x, 1024.0);
            ASSERT_GE(atlas.corners[t][c].y, 0.0);
            ASSERT_LE(atlas.corners[t][c].y, 512.0);
        }
    // No two triangles overlap: sample each triangle's interior (away from its edges)
    // and find no other triangle holding the sample.
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.05, 0.9);
    for (sim::TriId t = 0; t < nt; t += 7) {
        double b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 0.95) {
            b1 = 0.95 - b1;
            b2 = 0.95 - b2;
        }
        const auto &p = atlas.corners[t];
        const sim::Vec2d q = p[0] * (1 - b1 - b2) + p[1] * b1 + p[2] * b2;
        for (sim::TriId o = 0; o < nt; ++o) {
            if (o == t) continue;
            const sim::Vec3d b = barycentric(atlas.corners[o], q);
            ASSERT_FALSE(b.x > 1e-9 && b.y > 1e-9 && b.z > 1e-9)
                << "triangles " << t << " and " << o << " overlap";
        }
    }
}

TEST(Bake, AtlasUsesSeventyPercentOfTheTexelsOnTheCow) {
    const sim::Surface s = sim::build_surface(sample_mesh("cow.off"));
    const cm::Atlas atlas = cm::pack_atlas(s.crps, 4096, 4096);
    EXPECT_GE(atlas.coverage(), 0.70) << atlas.num_charts << " charts";
    EXPECT_LT(atlas.num_charts, s.mesh.num_triangles() / 4);
}

TEST(Bake, TexelsTakeTheShadersFilteredLookAndTheNearestCellsIds) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 500, 0.4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh_spec);
    const MosaicPluginInstance shader(nlohmann::json::object(), cells.c_str(), mesh_spec);
    ASSERT_TRUE(shader.self) << shader.error;
    const int res = 256;
    const cm::BakedAtlas baked = cm::bake_atlas(pattern, res, res);
    ASSERT_EQ(baked.image.tiles.size(), 1u);
    const std::vector<float> &px = baked.image.tiles[0].pixels;
    const int C = cm::BakeResult::channels;
    // The atlas is isometric: a texel is 1 / texels_per_unit wide on the surface.
    const float footprint = float(1 / baked.atlas.texels_per_unit);
    size_t centres = 0, blended = 0;
    for (sim::TriId t = 0; t < pattern.num_triangles(); t += 3) {
        const auto &p = baked.atlas.corners[t];
        const int x0 = int(std::min({p[0].x, p[1].x, p[2].x})),
                  x1 = int(std::max({p[0].x, p[1].x, p[2].x})),
                  y0 = int(std::min({p[0].y, p[1].y, p[2].y})),
                  y1 = int(std::max({p[0].y, p[1].y, p[2].y}));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const sim::Vec3d b = barycentric(p, {x + 0.5, y + 0.5});
                if (!(b.x > 1e-6 && b.y > 1e-6 && b.z > 1e-6)) continue;
                const float *texel = &px[(size_t(y) * res + x) * C];
                const PelageShade s = shader.shade(t, float(b.y), float(b.z), footprint);
                for (int k = 0; k < 3; ++k)
                    ASSERT_NEAR(texel[k], s.albedo[k], 1e-5) << t << " " << x << "," << y;
                ASSERT_EQ(texel[3], 1.0f);
                const pattern::mosaic::ClosestCell c =
                    pattern.index().find_nearest(t, float(b.y), float(b.z));
                ASSERT_EQ(texel[5], float(pattern.cells().id[c.index]));
                ASSERT_EQ(texel[4], float(pattern.cells().type[c.index]));
                blended += texel[0] != pattern.types()[0].colour[0] &&
                           texel[0] != pattern.types()[1].colour[0];
                ++centres;
            }
    }
    EXPECT_GT(centres, 3000u);
    EXPECT_GT(blended, 50u);  // cell edges are filtered, not point-sampled
}

TEST(Bake, NoTexelWithinTheGutterOfAChartStaysUncovered) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 300, 0.4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh_spec);
    const int res = 192, gutter = 4;
    const cm::BakedAtlas baked = cm::bake_atlas(pattern, res, res, gutter);
    const std::vector<float> &px = baked.image.tiles[0].pixels;
    const int C = cm::BakeResult::channels;
    size_t uncovered = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const float *texel = &px[(size_t(y) * res + x) * C];
            double nearest = 1e300;
            for (const auto &p : baked.atlas.corners)
                nearest = std::min(nearest, distance_to(p, {x + 0.5, y + 0.5}));
            if (nearest <= gutter - 1e-6) {
                ASSERT_EQ(texel[3], 1.0f)
                    << x << "," << y << " is " << nearest << " texels from a triangle";
                ASSERT_GE(texel[5], 0.0f);
            } else if (texel[3] == 0) {
                ++uncovered;
                // Beyond the gutters: a neighbour's colour, never black.
                ASSERT_GT(texel[0] + texel[1] + texel[2], 0.0f) << x << "," << y;
                ASSERT_EQ(texel[5], -1.0f);
            }
        }
    EXPECT_GT(uncovered, 0u);
    EXPECT_GT(baked.image.texels_gutter, 0u);
}

// A gutter texel shows the surface beyond its chart's border: the point its offset from
// the border reaches when the border triangle's plane is continued, brought back to the
// (nearly flat, at this scale) surface by its closest point. Clamping to the border
// instead would repeat the border's cells across the whole gutter.
TEST(Bake, GutterTexelsContinueTheSurfaceAcrossTheSeam) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 800, 0.4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh_spec);
    const int res = 256, gutter = 12;
    const cm::BakedAtlas baked = cm::bake_atlas(pattern, res, res, gutter);
    const std::vector<float> &px = baked.image.tiles[0].pixels;
    const int C = cm::BakeResult::channels;
    const sim::TriangleMesh &mesh = pattern.surface().mesh;
    const auto id_at = [&](sim::TriId t, sim::Vec3d b) {
        const pattern::mosaic::ClosestCell c =
            pattern.index().find_nearest(t, float(b.y), float(b.z));
        return float(pattern.cells().id[c.index]);
    };
    size_t far = 0, continued = 0, clamped = 0;
    for (int y = 0; y < res; y += 2)
        for (int x = 0; x < res; x += 2) {
            const float *texel = &px[(size_t(y) * res + x) * C];
            const sim::Vec2d q{x + 0.5, y + 0.5};
            double nearest = 1e300;
            sim::TriId t = 0;
            for (sim::TriId k = 0; k < mesh.num_triangles(); ++k)
                if (const double d = distance_to(baked.atlas.corners[k], q);
                    d < nearest) {
                    nearest = d;
                    t = k;
                }
            if (!(nearest > gutter / 2.0 && nearest <= gutter && texel[3] == 1)) continue;
            // The texel in t's plane, continued past its border (the atlas is isometric).
            const sim::Vec3d b = barycentric(baked.atlas.corners[t], q);
            const sim::Vec3d p = mesh.vertex(t, 0) * b.x + mesh.vertex(t, 1) * b.y +
                                 mesh.vertex(t, 2) * b.z;
            double best = 1e300;
            sim::TriId s = 0;
            sim::Vec3d on;
            for (sim::TriId k = 0; k < mesh.num_triangles(); ++k) {
                const sim::Vec3d c = sim::closest_point_on_triangle(
                    p, mesh.vertex(k, 0), mesh.vertex(k, 1), mesh.vertex(k, 2));
                if (length(c - p) < best) {
                    best = length(c - p);
                    s = k;
                    on = c;
                }
            }
            const sim::Vec2d a2 = pattern.surface().crps.to_2d(s, on);
            const sim::Vec3d bs = pattern.surface().crps.to_barycentric(s, a2);
            // The border point the texel would repeat if it were clamped.
            sim::Vec3d bc = b;
            const double lo = std::min({b.x, b.y, b.z});
            if (lo < 0) {
                bc = {std::max(b.x, 0.0), std::max(b.y, 0.0), std::max(b.z, 0.0)};
                const double sum = bc.x + bc.y + bc.z;
                bc = {bc.x / sum, bc.y / sum, bc.z / sum};
            }
            ++far;
            continued += texel[5] == id_at(s, bs);
            clamped += texel[5] == id_at(t, bc);
        }
    ASSERT_GT(far, 200u);
    EXPECT_GT(double(continued) / far, 0.9) << continued << " of " << far;
    EXPECT_LT(double(clamped) / far, double(continued) / far - 0.15)
        << clamped << " of " << far;
}

TEST(Bake, UvsOverSeveralUdimTilesBakeIntoThoseTiles) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 300, 0.4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh_spec);
    const cm::Atlas atlas = cm::pack_atlas(pattern.surface().crps, 128, 128);
    // The atlas's UVs, every other triangle moved one tile right and every third one
    // tile up: 1001, 1002, 1011, 1012.
    cm::BakeLayout layout;
    layout.mesh = &pattern.surface().mesh;
    layout.width = layout.height = 128;
    for (sim::TriId t = 0; t < pattern.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c)
            layout.corner_uvs.push_back(atlas.uv(t, c) +
                                        sim::Vec2d{double(t % 2), double(t % 3 == 0)});
    const cm::BakeResult baked = cm::bake_layout(pattern, layout);
    ASSERT_EQ(baked.tiles.size(), 4u);
    const int udims[4] = {1001, 1002, 1011, 1012};
    for (int k = 0; k < 4; ++k) EXPECT_EQ(baked.tiles[size_t(k)].udim, udims[k]);
    const int C = cm::BakeResult::channels;
    size_t checked = 0;
    for (sim::TriId t = 0; t < pattern.num_triangles(); t += 5) {
        const int tile = (t % 2 ? 1 : 0) + (t % 3 == 0 ? 2 : 0);
        const auto &p = atlas.corners[t];
        const sim::Vec2d centre = (p[0] + p[1] + p[2]) / 3;
        const int x = int(centre.x), y = int(centre.y);
        const sim::Vec3d b = barycentric(p, {x + 0.5, y + 0.5});
        if (!(b.x > 0 && b.y > 0 && b.z > 0)) continue;
        const pattern::mosaic::ClosestCell c =
            pattern.index().find_nearest(t, float(b.y), float(b.z));
        EXPECT_EQ(baked.tiles[size_t(tile)].pixels[(size_t(y) * 128 + x) * C + 5],
                  float(pattern.cells().id[c.index]))
            << t;
        ++checked;
    }
    EXPECT_GT(checked, 100u);

    layout.corner_uvs[7].x = 10.5;  // triangle 2, corner 1
    try {
        cm::bake_layout(pattern, layout);
        FAIL() << "UVs outside the UDIM range were accepted";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("triangle 2"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("1001-1100"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace pelage::test
