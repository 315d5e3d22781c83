// Closest-cell search (Teo 2006 §6.2): the pruned search equals the exhaustive one, it is
// the true Voronoi diagram where the surface is flat, and edge-adjacent triangles agree
// wherever their unfoldings agree.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shader/clonal_mosaic/closest_cell.h"
#include "sim/procedural_mesh.h"
#include "sim/surface.h"
#include "sim/surface_sampling.h"
#include "tests/test_paths.h"

namespace pelage::shader {
namespace {

CellTable random_cells(const sim::Crps &crps, size_t n, uint64_t seed) {
    std::vector<CellOnSurface> cells;
    uint32_t id = 0;
    for (const auto &s : sim::sample_surface_uniform(crps, n, seed)) {
        cells.push_back({s.tri, s.p.x, s.p.y, id, uint8_t(id % 2)});
        ++id;
    }
    return make_cell_table(crps.num_triangles(), cells);
}

Vec2f to_f(sim::Vec2d p) { return {float(p.x), float(p.y)}; }

// The bound: the pruned search equals the exhaustive search over the same
// unfolded neighbourhood on >= 99.99 % of random surface points.
void expect_pruned_equals_exhaustive(const sim::Surface &s, size_t n_cells) {
    const CellTable cells = random_cells(s.crps, n_cells, 5);
    const ClosestCellIndex index(s.crps, cells);
    const auto queries = sim::sample_surface_uniform(s.crps, 200000, 99);
    size_t agree = 0;
    for (const auto &q : queries) {
        const ClosestCell a = index.find(q.tri, to_f(q.p));
        const ClosestCell b = index.find_exhaustive(q.tri, to_f(q.p));
        ASSERT_NE(a.index, ClosestCell::none);
        agree += a.index == b.index && a.f1 == b.f1 && a.f2 == b.f2;
    }
    EXPECT_GE(double(agree) / queries.size(), 0.9999) << agree << " of " << queries.size();
}

TEST(ClosestCell, PrunedEqualsExhaustiveOnTheCow) {
    expect_pruned_equals_exhaustive(sim::build_surface(test::sample_mesh("cow.off")), 20000);
}

TEST(ClosestCell, PrunedEqualsExhaustiveOnTheTriceratops) {
    expect_pruned_equals_exhaustive(sim::build_surface(test::sample_mesh("triceratops.off")), 20000);
}

TEST(ClosestCell, PrunedEqualsExhaustiveOnThe760TriangleSphere) {
    // Few cells per triangle and many triangles per cell: both regimes of Teo §6.3.
    const sim::Surface s = sim::build_surface(sim::make_uv_sphere(20, 20));
    expect_pruned_equals_exhaustive(s, 10000);
    expect_pruned_equals_exhaustive(s, 100);
}

// On a flat mesh the unfolding is exact, so the search must return the true Euclidean
// nearest cell and second-nearest distance among all cells.
TEST(ClosestCell, FlatPlaneGivesTheTrueVoronoiDiagram) {
    const sim::Surface s = sim::build_surface(sim::make_plane(20, 20, 2, 2));
    const CellTable cells = random_cells(s.crps, 500, 3);
    const ClosestCellIndex index(s.crps, cells);
    std::vector<sim::Vec3d> world(cells.size());
    for (sim::TriId t = 0; t < s.mesh.num_triangles(); ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
            world[k] = s.crps.to_3d(t, {cells.x[k], cells.z[k]});
    for (const auto &q : sim::sample_surface_uniform(s.crps, 5000, 8)) {
        const sim::Vec3d p = s.crps.to_3d(q.tri, q.p);
        double d1 = 1e300, d2 = 1e300;
        uint32_t best = 0;
        for (uint32_t k = 0; k < world.size(); ++k) {
            const double d = length(world[k] - p);
            if (d < d1) { d2 = d1; d1 = d; best = k; } else if (d < d2) { d2 = d; }
        }
        const ClosestCell c = index.find(q.tri, to_f(q.p));
        ASSERT_EQ(c.index, best);
        ASSERT_NEAR(c.f1, d1, 1e-5);
        ASSERT_NEAR(c.f2, d2, 1e-5);
    }
}

TEST(ClosestCell, EveryPointFindsACellEvenWithOneCellOnTheSurface) {
    const sim::Surface s = sim::build_surface(sim::make_icosphere(2));
    const CellTable cells = random_cells(s.crps, 1, 1);
    const ClosestCellIndex index(s.crps, cells);
    for (const auto &q : sim::sample_surface_uniform(s.crps, 2000, 4))
        ASSERT_EQ(index.find(q.tri, to_f(q.p)).index, 0u);
}

// Points a hair apart on either side of every shared edge must agree on the nearest cell
// wherever the two triangles' unfoldings agree on the competing cells (they measure the
// same distances); disagreements elsewhere are Teo's cracks (§6.3), counted, not failed.
TEST(ClosestCell, EdgeNeighboursAgreeWhereTheirUnfoldingsAgree) {
    const sim::Surface s = sim::build_surface(test::sample_mesh("cow.off"));
    const CellTable cells = random_cells(s.crps, 20000, 5);
    const ClosestCellIndex index(s.crps, cells);
    const sim::Topology &topo = s.crps.topology();
    size_t samples = 0, cracks = 0, inconsistent = 0;
    for (sim::EdgeId e = 0; e < topo.num_edges(); ++e) {
        if (!topo.is_manifold(e)) continue;
        const auto f = topo.faces_of_edge(e);
        const sim::Vec3d a = s.mesh.positions[topo.edge_vertices[e][0]];
        const sim::Vec3d b = s.mesh.positions[topo.edge_vertices[e][1]];
        for (double u : {0.2, 0.5, 0.8}) {
            const sim::Vec3d p = a + (b - a) * u;
            const Vec2f qa = to_f(s.crps.to_2d(f[0], p)), qb = to_f(s.crps.to_2d(f[1], p));
            const ClosestCell ca = index.find(f[0], qa), cb = index.find(f[1], qb);
            ++samples;
            if (ca.index == cb.index) continue;
            ++cracks;
            // Same distances to both competitors from both sides: then only a near-tie
            // may explain different answers.
            const float a1 = index.distance_to_cell(f[0], qa, ca.index), a2 = index.distance_to_cell(f[0], qa, cb.index);
            const float b1 = index.distance_to_cell(f[1], qb, ca.index), b2 = index.distance_to_cell(f[1], qb, cb.index);
            const float tol = 1e-5f * (a1 + 1e-6f);
            const bool unfoldings_agree = std::abs(a1 - b1) <= tol && std::abs(a2 - b2) <= tol;
            if (unfoldings_agree && std::abs(a1 - a2) > 2 * tol) ++inconsistent;
        }
    }
    EXPECT_EQ(inconsistent, 0u);
    std::printf("edge samples %zu, cracks %zu (%.4f %%)\n", samples, cracks, 100.0 * cracks / samples);
    // Measured 4.1 % with edge-only unfolding (13.5 % with Teo's vertex maps); this bound
    // catches a regression to the latter.
    EXPECT_LT(double(cracks) / samples, 0.06);
}

}  // namespace
}  // namespace pelage::shader
