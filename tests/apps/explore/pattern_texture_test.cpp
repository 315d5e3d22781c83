// The explorer's type texture (apps/explore/pattern_texture.h): on a flat surface,
// where geodesic distance is Euclidean, every texel holds the type of the nearest cell by
// brute force in 3D; on the cow, what a view's nearest filtering reads at any point of a
// triangle is a sample of that triangle (no tile bleeds into another).
#include "apps/explore/pattern_texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/test_paths.h"

namespace pelage::renderer::explore {
namespace {

// Cells at random surface points, their types by index, as a .cells file holds them.
sim::CellsData random_cells(const sim::Crps &crps, size_t n, int types, uint64_t seed) {
    std::vector<std::vector<sim::SurfacePointSample>> by_tri(crps.num_triangles());
    for (const auto &s : sim::sample_surface_uniform(crps, n, seed))
        by_tri[s.tri].push_back(s);
    sim::CellsData d;
    for (size_t t = 0; t < crps.num_triangles(); ++t) d.frames.push_back(crps.frame(t));
    d.cell_row.push_back(0);
    uint32_t id = 0;
    for (const auto &cells : by_tri) {
        for (const auto &s : cells) {
            d.x.push_back(s.p.x);
            d.z.push_back(s.p.y);
            d.id.push_back(id);
            d.type.push_back(uint8_t(id % types));
            ++id;
        }
        d.cell_row.push_back(uint32_t(d.x.size()));
    }
    return d;
}

sim::Vec3d on_mesh(const sim::TriangleMesh &m, sim::TriId t, double b1, double b2) {
    const auto &tri = m.triangles[t];
    return m.positions[tri[0]] * (1 - b1 - b2) + m.positions[tri[1]] * b1 +
           m.positions[tri[2]] * b2;
}

TEST(TypeTexture, EveryTexelHoldsTheNearestCellsTypeOnAPlane) {
    const sim::Surface s = sim::build_surface(sim::make_plane(12, 12, 1.0, 1.0));
    const sim::CellsData cells = random_cells(s.crps, 300, 3, 7);
    // The cells in 3D, from their local coordinates.
    std::vector<sim::Vec3d> at;
    std::vector<uint8_t> type;
    for (sim::TriId t = 0; t < cells.num_triangles(); ++t)
        for (uint32_t k = cells.cell_row[t]; k < cells.cell_row[t + 1]; ++k) {
            const sim::Vec3d b =
                sim::barycentric_in(s.crps.frame(t), {cells.x[k], cells.z[k]});
            at.push_back(on_mesh(s.mesh, t, b.y, b.z));
            type.push_back(cells.type[k]);
        }
    const TypeTextureLayout layout = layout_type_texture(s.mesh, 256);
    const std::vector<uint8_t> tex = type_texture(layout, s.crps, cells);
    size_t checked = 0, agree = 0, covered = 0;
    for (uint8_t v : tex) covered += v != no_type;
    for (size_t i = 0; i < layout.texel.size(); ++i) {
        const sim::Vec3d p = on_mesh(s.mesh, layout.tri[i], layout.b1[i], layout.b2[i]);
        double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
        int best = -1;
        for (size_t c = 0; c < at.size(); ++c) {
            const double d = length(at[c] - p);
            if (d < d1) {
                d2 = d1;
                d1 = d;
                best = int(c);
            } else if (d < d2) {
                d2 = d;
            }
        }
        if (d2 - d1 < 1e-5) continue;  // a tie within float precision
        ++checked;
        agree += tex[layout.texel[i]] == type[best];
    }
    EXPECT_GT(checked, layout.texel.size() * 99 / 100);
    EXPECT_EQ(agree, checked);
    // Every texel of every tile, and only those: the samples and the rest of the tiles.
    EXPECT_EQ(covered, layout.texel.size() + layout.fill.size());
}

TEST(TypeTexture, NearestFilteringReadsTheFragmentsOwnTriangleOnTheCow) {
    const sim::Surface s = sim::build_surface(test::sample_mesh("cow.off"));
    const int size = 1024;
    const TypeTextureLayout layout = layout_type_texture(s.mesh, size);
    std::vector<sim::TriId> owner(size_t(size) * size, sim::invalid_id);
    for (size_t i = 0; i < layout.texel.size(); ++i) {
        ASSERT_EQ(owner[layout.texel[i]], sim::invalid_id) << "texel used twice";
        owner[layout.texel[i]] = layout.tri[i];
    }
    // Random points of random triangles, through the corners' UVs as a rasteriser
    // interpolates them, read with nearest filtering: floor(uv · size).
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    std::uniform_int_distribution<uint32_t> pick(0, uint32_t(s.mesh.num_triangles() - 1));
    for (int n = 0; n < 200000; ++n) {
        const sim::TriId t = pick(rng);
        float b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
        const float *c = &layout.corner_uvs[6 * t];
        const float uu = c[0] * (1 - b1 - b2) + c[2] * b1 + c[4] * b2;
        const float vv = c[1] * (1 - b1 - b2) + c[3] * b1 + c[5] * b2;
        const int x = int(std::floor(uu * size)), y = int(std::floor(vv * size));
        ASSERT_TRUE(x >= 0 && x < size && y >= 0 && y < size);
        ASSERT_EQ(owner[size_t(y) * size + x], t)
            << "triangle " << t << " at " << b1 << ", " << b2;
    }
    // Texels are about one size on the surface: the longest edge's per texel.
    EXPECT_GT(layout.texel_length, 0);
    EXPECT_LT(layout.texel.size(), size_t(size) * size);
}

TEST(TypeTexture, RefusesATextureTooSmallForTheMesh) {
    const sim::TriangleMesh m = sim::make_plane(30, 30, 1.0, 1.0);  // 1 800 triangles
    EXPECT_THROW(layout_type_texture(m, 64), std::invalid_argument);
}

}  // namespace
}  // namespace pelage::renderer::explore
