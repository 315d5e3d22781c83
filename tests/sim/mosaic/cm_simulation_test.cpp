// The Clonal Mosaic simulation: relaxation spaces cells evenly, cells stay on the
// surface, divisions follow the Poisson mean, results do not depend on thread count.
#include "sim/mosaic/cm_simulation.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <random>

#include "sim/cells_io/cells_file.h"
#include "sim/core/random.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/preset.h"
#include "sim/run/cells_data.h"
#include "tests/sim/sim_test_util.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

void expect_all_inside(const Crps &crps, const Cells &cells) {
    for (CellId c = 0; c < cells.size(); ++c) {
        ASSERT_GE(min_barycentric(crps.frame(cells.tri(c)), cells.pos(c)), -1e-9)
            << "cell " << c;
        // The bucket of its triangle lists it.
        const auto &b = cells.on(cells.tri(c));
        ASSERT_NE(std::find(b.begin(), b.end(), c), b.end());
    }
}

TEST(Relaxation, SingleTypeConvergesTowardUniformSpacing) {
    const Surface s = build_surface("procedural:sphere:20x20");
    const Preset p = parse_preset(
        test::preset_json(
            R"({"initial_cells": 600, "initial_relax_steps": 0, "w_r": 2.0, "w_d": 0.1, "rho": 1, "end_time": 0})"),
        "t");
    CmSimulation sim(s.crps, p.types, p.params, 3);
    sim.initialize();
    const double cv_random = test::nearest_neighbour_cv(s.crps, sim.cells());
    std::vector<TriId> all(s.mesh.num_triangles());
    for (TriId t = 0; t < all.size(); ++t) all[t] = t;
    for (int k = 0; k < 150; ++k) sim.relax(all, false);
    const double cv_relaxed = test::nearest_neighbour_cv(s.crps, sim.cells());
    // Uniform random points have CV ≈ 0.52 (Poisson process); a relaxed, nearly
    // hexagonal arrangement is well below 0.2.
    EXPECT_GT(cv_random, 0.35);
    EXPECT_LT(cv_relaxed, 0.2) << "random " << cv_random;
    expect_all_inside(s.crps, sim.cells());
}

TEST(CmSimulation, CellsStayOnTheCowAndOnAnOpenMesh) {
    for (const std::string &mesh :
         {test::sample_mesh("cow.off"), std::string("procedural:plane:10x10")}) {
        const Surface s = build_surface(mesh);
        const Preset p = parse_preset(
            test::preset_json(
                R"({"initial_cells": 1500, "initial_relax_steps": 10, "w_r": 2.4, "w_d": 0.2, "rho": 4, "end_time": 6})",
                true, "3"),
            "t");
        for (RelaxMode mode : {RelaxMode::local, RelaxMode::global}) {
            SimParams params = p.params;
            params.relax = mode;
            CmSimulation sim(s.crps, p.types, params, 11);
            sim.initialize();
            sim.run();
            EXPECT_GT(sim.stats().divisions, 100u) << mesh;
            EXPECT_EQ(sim.cells().size(), 1500 + sim.stats().divisions);
            expect_all_inside(s.crps, sim.cells());
        }
    }
}

// Expected cells descending from one newborn cell by time T when inter-division delays
// are Poisson(mu) integers: m(T) = P(X > T) + Σ_{k ≤ T} P(X = k)·2·m(T − k).
double expected_cells(double mu, int T) {
    std::vector<double> pk(T + 1);
    double p = std::exp(-mu);
    for (int k = 0; k <= T; ++k) {
        pk[k] = p;
        p *= mu / (k + 1);
    }
    std::vector<double> m(T + 1);
    for (int t = 0; t <= T; ++t) {
        double tail = 1, sum = 0;
        for (int k = 0; k <= t; ++k) {
            tail -= pk[k];
            if (k >= 1) sum += pk[k] * 2 * m[t - k];  // k = 0 is raised to one step
        }
        m[t] = tail + pk[0] + sum;  // a zero delay counts as "not yet" (P ≈ e^-mu)
    }
    return m[T];
}

TEST(CmSimulation, DivisionCountsFollowThePoissonMean) {
    const Surface s = build_surface("procedural:sphere:8x8");
    const int T = 15;
    const double mu = 10;
    const Preset p = parse_preset(
        test::preset_json(
            R"({"initial_cells": 400, "initial_relax_steps": 0, "w_r": 1.0, "w_d": 0.05, "rho": 1, "end_time": 15, "relax": "local", "local_steps": 1})",
            false, "10"),
        "t");
    CmSimulation sim(s.crps, p.types, p.params, 5);
    sim.initialize();
    sim.run();
    const double expected = 400 * (expected_cells(mu, T) - 1);
    // Per initial cell the count has a standard deviation below 1; over 400 cells the
    // mean is known to ±0.05 per cell: 10 % is > 4 sigma.
    EXPECT_NEAR(double(sim.stats().divisions), expected, 0.1 * expected);
}

TEST(Random, PoissonDeviatesHaveTheRightMeanAndVariance) {
    for (double mu : {0.7, 10.0, 150.0}) {
        double sum = 0, sum2 = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            CounterRng rng(1, RandomStream::division, i);
            const double k = double(rng.poisson(mu));
            sum += k;
            sum2 += k * k;
        }
        const double mean = sum / n, var = sum2 / n - mean * mean;
        EXPECT_NEAR(mean, mu, 5 * std::sqrt(mu / n)) << mu;
        EXPECT_NEAR(var, mu, 0.06 * mu)
            << mu;  // sd of the variance estimate ≈ mu·sqrt(2/n)
    }
}

TEST(CmSimulation, MutationFollowsTheParentRow) {
    const Surface s = build_surface("procedural:sphere:8x8");
    const Preset p = parse_preset(R"({"name": "m", "types": [
        {"name": "F", "colour": [0,0,0], "division_time": 1, "initial_probability": 1},
        {"name": "M", "colour": [1,1,1], "division_time": "never", "initial_probability": 0}],
        "mutation": [[0.3, 0.7], [0, 1]], "adhesion": [[0.5, 0.5], [0.5, 0.5]],
        "simulation": {"initial_cells": 2000, "initial_relax_steps": 0, "w_r": 1, "w_d": 0.05, "rho": 1, "end_time": 1, "local_steps": 1}})",
                                  "t");
    CmSimulation sim(s.crps, p.types, p.params, 9);
    sim.initialize();
    sim.run();
    const auto n = sim.count_by_type();
    const double divisions = double(sim.stats().divisions);
    ASSERT_GT(divisions, 300);
    // Every child of an F parent is M with probability 0.7 (binomial, 4 sigma).
    EXPECT_NEAR(double(n[1]) / divisions, 0.7, 4 * std::sqrt(0.21 / divisions));
}

std::vector<uint8_t> run_with_threads(int threads, RelaxMode mode) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);
    const Surface s = build_surface("procedural:sphere:20x20");
    const Preset p = parse_preset(
        test::preset_json(
            R"({"initial_cells": 1200, "initial_relax_steps": 5, "w_r": 2.0, "w_d": 0.1, "rho": 10, "end_time": 1.5})",
            true, "0.8"),
        "t");
    SimParams params = p.params;
    params.relax = mode;
    CmSimulation sim(s.crps, p.types, params, 42);
    sim.initialize();
    sim.run();
    return serialize_cells(
        make_cells_data(s.mesh, s.crps, sim.types(), sim.cells(), "{}", 42));
}

TEST(CmSimulation, IdenticalCellsAtOneAndTwoThreads) {
    for (RelaxMode mode : {RelaxMode::local, RelaxMode::global}) {
        const auto one = run_with_threads(1, mode), two = run_with_threads(2, mode);
        EXPECT_EQ(one.size(), two.size());
        EXPECT_TRUE(one == two);
    }
}

TEST(CmSimulation, LocalAndGlobalAgreeOnCounts) {
    // Divisions do not depend on positions: both modes give the same counts.
    const auto l = parse_cells(run_with_threads(2, RelaxMode::local), "l");
    const auto g = parse_cells(run_with_threads(2, RelaxMode::global), "g");
    EXPECT_EQ(l.num_cells(), g.num_cells());
    EXPECT_EQ(std::count(l.type.begin(), l.type.end(), 0),
              std::count(g.type.begin(), g.type.end(), 0));
}

}  // namespace
}  // namespace pelage::sim

namespace pelage::sim {
namespace {

TEST(Relaxation, FullAnisotropyMovesCellsOnlyAlongTheField) {
    // w_a = 1: C' = C + O with O the projection of D on A (SG01 §3.2.1). On a flat plane
    // with A along world X, no cell may move in Z.
    const Surface s = build_surface("procedural:plane:6x6");
    const Preset p = parse_preset(
        test::preset_json(
            R"({"initial_cells": 200, "initial_relax_steps": 0, "w_r": 2.0, "w_d": 0.1, "w_a": 1.0,
            "anisotropy": {"direction": [1, 0, 0], "magnitude": 0.1}, "rho": 1, "end_time": 0})"),
        "t");
    CmSimulation sim(s.crps, p.types, p.params, 2);
    sim.initialize();
    std::vector<Vec3d> before;
    for (CellId c = 0; c < sim.cells().size(); ++c)
        before.push_back(s.crps.to_3d(sim.cells().tri(c), sim.cells().pos(c)));
    std::vector<TriId> all(s.mesh.num_triangles());
    for (TriId t = 0; t < all.size(); ++t) all[t] = t;
    for (int k = 0; k < 10; ++k) sim.relax(all, false);
    double moved_x = 0;
    for (CellId c = 0; c < sim.cells().size(); ++c) {
        const Vec3d q = s.crps.to_3d(sim.cells().tri(c), sim.cells().pos(c));
        EXPECT_NEAR(q.z, before[c].z, 1e-9) << c;
        moved_x += std::abs(q.x - before[c].x);
    }
    EXPECT_GT(moved_x, 1e-3);  // and they did move along X
}

}  // namespace
}  // namespace pelage::sim

namespace pelage::sim {
namespace {

TEST(LocalRelaxation, OnlyTrianglesNearDivisionsAreRelaxed) {
    // Teo §5.1.4: without divisions nothing is marked, so local steps move no cell;
    // global steps do.
    const Surface s = build_surface("procedural:sphere:12x12");
    const Preset p = parse_preset(
        test::preset_json(
            R"({"initial_cells": 300, "initial_relax_steps": 0, "w_r": 2.0, "w_d": 0.1, "rho": 1, "end_time": 5})"),
        "t");
    for (RelaxMode mode : {RelaxMode::local, RelaxMode::global}) {
        SimParams params = p.params;
        params.relax = mode;
        CmSimulation sim(s.crps, p.types, params, 8);
        sim.initialize();
        const std::vector<double> x0 = sim.cells().x();
        sim.run();
        EXPECT_EQ(sim.stats().relax_steps, 5u);
        EXPECT_EQ(sim.stats().divisions, 0u);
        if (mode == RelaxMode::local)
            EXPECT_EQ(sim.cells().x(), x0);
        else
            EXPECT_NE(sim.cells().x(), x0);
    }
}

TEST(LocalRelaxation, ADivisionRelaxesItsNeighbourhoodForSSteps) {
    // One dividing cell among still ones: the local run relaxes fewer cell-steps than
    // the global one, and more than zero.
    const Surface s = build_surface("procedural:sphere:20x20");
    const Preset p = parse_preset(R"({"name": "one", "types": [
        {"name": "F", "colour": [0,0,0], "division_time": 3, "initial_probability": 0.01},
        {"name": "B", "colour": [1,1,1], "division_time": "never", "initial_probability": 0.99}],
        "adhesion": [[0.5, 0.0], [0.0, 0.5]],
        "simulation": {"initial_cells": 2000, "initial_relax_steps": 0, "w_r": 2, "w_d": 0.1, "rho": 4, "end_time": 4,
                       "division_distribution": "exponential", "local_steps": 3}})",
                                  "t");
    uint64_t steps[2];
    for (RelaxMode mode : {RelaxMode::local, RelaxMode::global}) {
        SimParams params = p.params;
        params.relax = mode;
        CmSimulation sim(s.crps, p.types, params, 8);
        sim.initialize();
        sim.run();
        ASSERT_GT(sim.stats().divisions, 0u);
        steps[mode == RelaxMode::local ? 0 : 1] = sim.stats().cell_steps;
    }
    EXPECT_GT(steps[0], 0u);
    EXPECT_LT(steps[0] * 4, steps[1]);
}

}  // namespace
}  // namespace pelage::sim

namespace pelage::sim {
namespace {

SurfacePoint locate(const Crps &crps, Vec3d p) {
    for (TriId t = 0; t < crps.num_triangles(); ++t) {
        const Vec2d q = crps.to_2d(t, p);
        if (min_barycentric(crps.frame(t), q) >= 0 && length(crps.to_3d(t, q) - p) < 1e-9)
            return {t, q};
    }
    ADD_FAILURE() << "point not on the mesh";
    return {};
}

TEST(Relaxation, TwoCellsOnDifferentTrianglesRepelExactlyAsInWalter) {
    // Walter 1998 Fig. 1 on a flat mesh (maps are exact there): two cells at distance d
    // < r on different triangles each move by w_d·(1 − d/r)·(1 − α)·r, away from each
    // other along the line joining them.
    const Surface s = build_surface("procedural:plane:8x8");
    const CellTypes types({CellType{"F", {0, 0, 0}, 0, 0, 1.0, 1.0}}, {{1.0}}, {{0.25}});
    Cells cells(s.mesh.num_triangles());
    const Vec3d a{-0.13, 0, 0.02}, b{0.11, 0, -0.05};
    const SurfacePoint pa = locate(s.crps, a), pb = locate(s.crps, b);
    ASSERT_NE(pa.tri, pb.tri);
    cells.add(pa, 0);
    cells.add(pb, 0);
    RelaxContext ctx;
    ctx.crps = &s.crps;
    ctx.types = &types;
    ctx.r = 0.5;
    ctx.w_d = 0.2;
    Relaxer relaxer;
    relaxer.step(ctx, cells, {pa.tri, pb.tri});
    const double d = length(b - a);
    const double step = ctx.w_d * (1 - d / ctx.r) * (1 - 0.25) * ctx.r;
    const Vec3d u = (b - a) / d;
    const Vec3d a1 = s.crps.to_3d(cells.tri(0), cells.pos(0)),
                b1 = s.crps.to_3d(cells.tri(1), cells.pos(1));
    // The pair forces are summed in floats (pair_forces.h): 1e-7 of the frame's size.
    EXPECT_NEAR(length(a1 - (a - u * step)), 0, 1e-6 * ctx.r);
    EXPECT_NEAR(length(b1 - (b + u * step)), 0, 1e-6 * ctx.r);
}

// A whole step on a flat mesh, where 3D distances are the geodesic ones: every cell moves
// by w_d·Σ unit(C − P)·(1 − d/r)·(1 − α[C][P])·r over every other cell within r, summed
// here in doubles over all pairs, whatever triangles and chunks the cells lie in. Two
// cells placed on one point separate along opposite directions by w_d·(1 − α)·r each,
// on top of what the others do to them.
TEST(Relaxation, AStepMovesEveryCellByWaltersSumOverAllCellsWithinR) {
    const Surface s = build_surface("procedural:plane:8x8");
    const CellTypes types({CellType{"F", {0, 0, 0}, 0, 0, 1.0, 1.0},
                           CellType{"B", {1, 1, 1}, 0, 0, 1.0, 0.0}},
                          {{1.0, 0.0}, {0.0, 1.0}}, {{0.2, 0.6}, {0.5, 0.1}});
    Cells cells(s.mesh.num_triangles());
    std::vector<Vec3d> at;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (int i = 0; i < 300; ++i) {
        const Vec3d p{u(rng), 0, u(rng)};
        at.push_back(p);
        cells.add(locate(s.crps, p), static_cast<uint8_t>(i % 3 == 0));
    }
    at.push_back(at[10]);  // one on top of another
    cells.add(locate(s.crps, at.back()), 1);
    RelaxContext ctx;
    ctx.crps = &s.crps;
    ctx.types = &types;
    ctx.r = 0.11;
    ctx.w_d = 0.05;
    std::vector<TriId> all(s.mesh.num_triangles());
    for (TriId t = 0; t < all.size(); ++t) all[t] = t;
    Relaxer relaxer;
    relaxer.step(ctx, cells, all);
    size_t pairs = 0;
    Vec3d residual[2];
    for (CellId c = 0; c < cells.size(); ++c) {
        Vec3d D{0, 0, 0};
        for (CellId p = 0; p < cells.size(); ++p) {
            const double d = length(at[c] - at[p]);
            if (p == c || d >= ctx.r || d == 0) continue;
            D += (at[c] - at[p]) / d *
                 ((1 - d / ctx.r) * types.one_minus_alpha(cells.type(c), cells.type(p)) *
                  ctx.r);
            ++pairs;
        }
        const Vec3d moved = s.crps.to_3d(cells.tri(c), cells.pos(c)) - at[c];
        const Vec3d off = moved - D * ctx.w_d;
        if (c == 10 || c == cells.size() - 1) {
            residual[c == 10 ? 0 : 1] = off;
            continue;
        }
        ASSERT_NEAR(length(off), 0, 1e-6 * ctx.r) << "cell " << c;
    }
    EXPECT_GT(pairs, 3000u);
    EXPECT_NEAR(length(residual[0]), ctx.w_d * types.one_minus_alpha(0, 1) * ctx.r,
                1e-6 * ctx.r);
    EXPECT_NEAR(length(residual[1]), ctx.w_d * types.one_minus_alpha(1, 0) * ctx.r,
                1e-6 * ctx.r);
    EXPECT_NEAR(
        dot(residual[0], residual[1]) / (length(residual[0]) * length(residual[1])), -1,
        1e-6);
}

}  // namespace
}  // namespace pelage::sim

namespace pelage::sim {
namespace {

// The event loop divides the cell whose event is due, at that event's time: with one
// fast-dividing F cell and one B cell that divides after ~1000 time units, a run to
// t = 6 grows only the F lineage. (Dividing whichever event heads the heap after the
// due one is popped loses the F lineage and divides B early instead: F = 1, B = 2.)
TEST(CmSimulation, TheDueCellDividesAndNoOther) {
    const Surface s = build_surface("procedural:sphere:8x8");
    const Preset p = parse_preset(
        R"({"name": "due", "types": [
              {"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": 1, "initial_probability": 0.5},
              {"name": "B", "colour": [0.9, 0.7, 0.3], "division_time": 1000, "initial_probability": 0.5}],
            "adhesion": [[0.5, 0.5], [0.5, 0.5]],
            "simulation": {"initial_cells": 2, "initial_relax_steps": 0, "w_r": 1.0,
                           "w_d": 0.05, "rho": 1, "end_time": 6}})",
        "due");
    for (uint64_t seed : {1, 2, 3, 4, 5}) {
        CmSimulation sim(s.crps, p.types, p.params, seed);
        sim.initialize();
        ASSERT_EQ(sim.count_by_type(), (std::vector<size_t>{1, 1}));
        sim.run();
        const std::vector<size_t> n = sim.count_by_type();
        EXPECT_GE(sim.stats().divisions, 1u) << "seed " << seed;
        EXPECT_EQ(n[0], 1 + sim.stats().divisions) << "seed " << seed;
        EXPECT_EQ(n[1], 1u) << "seed " << seed;
    }
}

}  // namespace
}  // namespace pelage::sim
