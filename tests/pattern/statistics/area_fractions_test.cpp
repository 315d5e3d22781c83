// Area fractions (pattern/statistics/area_fractions.h) against a brute-force oracle:
// the same surface points, each given the type of the cell nearest to it in 3D. On a
// closed, nearly spherical mesh the straight-line and the surface nearest cell differ
// only in slivers along cell borders that cross mesh edges.
#include "pattern/statistics/area_fractions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sim/crps/surface_sampling.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// Each point's nearest cell by straight-line distance over every cell: no index, no
// unfolding, nothing shared with the search but the cell table.
std::vector<double> brute_force_fractions(const pattern::mosaic::MosaicPattern &p,
                                          size_t samples, uint64_t seed) {
    const sim::Crps &crps = p.surface().crps;
    const pattern::mosaic::CellTable &cells = p.cells();
    std::vector<sim::Vec3d> at(cells.size());
    for (sim::TriId t = 0; t < cells.num_triangles(); ++t)
        for (uint32_t c = cells.row[t]; c < cells.row[t + 1]; ++c)
            at[c] = crps.to_3d(t, {cells.x[c], cells.z[c]});
    std::vector<double> count(p.types().size(), 0);
    const auto points = sim::sample_surface_uniform(crps, samples, seed);
    for (const auto &s : points) {
        const sim::Vec3d q = crps.to_3d(s.tri, s.p);
        double best = std::numeric_limits<double>::infinity();
        size_t nearest = 0;
        for (size_t c = 0; c < at.size(); ++c) {
            const double d = sim::length_squared(at[c] - q);
            if (d < best) best = d, nearest = c;
        }
        ++count[cells.type[nearest]];
    }
    for (double &c : count) c /= double(points.size());
    return count;
}

TEST(AreaFractions, AgreeWithTheStraightLineNearestCell) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";  // 1280 triangles
    const std::string cells = simulate_two_type_cells(tmp, mesh, 1200, 0.3, 4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh);
    const size_t n = 40000;
    const auto a = pattern::statistics::measure_area_fractions(pattern, n, 9);
    const std::vector<double> oracle = brute_force_fractions(pattern, n, 9);
    ASSERT_EQ(a.samples, n);
    ASSERT_EQ(a.by_type.size(), 2u);
    EXPECT_NEAR(a.by_type[0] + a.by_type[1], 1.0, 1e-12);
    for (size_t k = 0; k < 2; ++k) EXPECT_NEAR(a.by_type[k], oracle[k], 0.005) << k;
    // Equal adhesion within each type packs both alike: area follows the 30 % count.
    EXPECT_NEAR(a.by_type[0], 0.3, 0.03);
}

TEST(AreaFractions, DeterministicForASeedAndConvergingWithSamples) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:2";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 600, 0.5, 2);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh);
    const auto a = pattern::statistics::measure_area_fractions(pattern, 20000, 5);
    const auto b = pattern::statistics::measure_area_fractions(pattern, 20000, 5);
    EXPECT_EQ(a.by_type, b.by_type);
    // Two seeds differ by sampling noise only: 5 standard errors of the difference.
    const auto c = pattern::statistics::measure_area_fractions(pattern, 20000, 6);
    const double se = std::sqrt(2 * 0.25 / 20000);
    EXPECT_NEAR(a.by_type[0], c.by_type[0], 5 * se);
}

}  // namespace
}  // namespace pelage::test
