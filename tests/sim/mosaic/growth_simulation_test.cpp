// The Clonal Mosaic on a growing surface (Walter thesis §6.2): cells per unit area stays
// within 10 % of its initial value while a sphere scales and a cylinder stretches
// (areas against the analytic ones), cells keep their barycentric points across a
// reshape, the run is the same at one and two threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/cm_simulation.h"
#include "sim/mosaic/growing_surface.h"
#include "sim/mosaic/preset.h"
#include "sim/run/cells_data.h"
#include "tests/sim/mosaic/growth_test_util.h"

namespace pelage::sim {
namespace {

// Two dividing types, F three times as fast as B (Walter's worked example, L1502).
std::string growing_preset(const std::string &growth, double end_time) {
    return R"({"name": "g", "types": [
      {"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": 4, "initial_probability": 0.3},
      {"name": "B", "colour": [0.9, 0.7, 0.3], "division_time": 12, "initial_probability": 0.7}],
      "adhesion": [[0.8, 0.0], [0.0, 0.4]],
      "simulation": {"initial_cells": 1200, "initial_relax_steps": 10, "w_r": 2.0,
                     "w_d": 0.1, "rho": 6, "end_time": )" +
           std::to_string(end_time) + R"(, "division_distribution": "exponential"},
      "growth": )" +
           growth + "}";
}

struct GrowingRun {
    std::vector<GrowthSample> samples;
    std::vector<size_t> by_type;
    double lost = 0;
    std::vector<uint8_t> bytes;  // the .cells data on the rest shape
};

GrowingRun run_growing(const std::string &mesh, const std::string &growth,
                       double end_time, uint64_t seed = 7) {
    const Surface s = build_surface(mesh);
    const Preset p = parse_preset(growing_preset(growth, end_time), "g.json");
    GrowingSurface growing(s.mesh, s.crps, resolve_growth(*p.growth, s.mesh, s.mesh));
    CmSimulation sim(growing.crps(), p.types, p.params, seed);
    sim.set_growth(&growing);
    sim.initialize();
    sim.run();
    GrowingRun r;
    r.samples = sim.stats().growth;
    r.by_type = sim.count_by_type();
    r.lost = sim.stats().growth_lost_cells;
    Cells on_rest = sim.cells();
    carry_cells(growing.crps(), s.crps, on_rest);
    r.bytes = serialize_cells(
        make_cells_data(s.mesh, s.crps, sim.types(), on_rest, "{}", seed));
    return r;
}

double max_deviation(const GrowingRun &r) {
    return test::max_density_deviation(r.samples);
}

void expect_density_within(const GrowingRun &r, double tolerance) {
    test::expect_density_within(r.samples, tolerance);
}

TEST(GrowingSimulation, DensityStaysConstantOnAUniformlyScaledSphere) {
    // Radius 0.5 → 1 over 12 time units: the area quadruples.
    const GrowingRun r = run_growing(
        "procedural:sphere:24x24",
        R"({"keys": [{"age": 0, "scale": 0.5}, {"age": 12, "scale": 1}]})", 12);
    ASSERT_EQ(r.samples.size(), 13u);  // one reshape per time unit, and the end
    EXPECT_NEAR(r.samples.back().area / r.samples.front().area, 4.0, 1e-9);
    RecordProperty("max_density_deviation", std::to_string(max_deviation(r)));
    expect_density_within(r, 0.10);
    // Analytic: the cells quadruple too (the Poisson spread of ~3600 divisions is 1 %).
    EXPECT_NEAR(double(r.samples.back().cells) / 1200.0, 4.0, 0.4);
    // Both types divided, F faster per cell (g_F = 3 g_B): F's share grows from 0.3.
    EXPECT_GT(double(r.by_type[0]) / double(r.by_type[0] + r.by_type[1]), 0.3);
    EXPECT_LT(r.lost, 1.0);
}

TEST(GrowingSimulation, DensityStaysConstantOnAStretchingCylinder) {
    // The open cylinder of radius 1 and height 2 about Y, inside one growth cylinder:
    // its length grows ×3 and its radius ×1.5 over 10 time units, linearly, so every
    // facet's area grows by L(t)·R(t) with L = 1 + 0.2 t, R = 1 + 0.05 t.
    const std::string growth = R"({"cylinders": [{"name": "c", "from": [0, -1.01, 0],
        "to": [0, 1.01, 0], "radius": 1.5}],
        "keys": [{"age": 0, "cylinders": {}},
                 {"age": 10, "cylinders": {"c": {"length": 3, "radius": 1.5}}}]})";
    const GrowingRun r = run_growing("procedural:cylinder:48x16", growth, 10);
    ASSERT_EQ(r.samples.size(), 11u);
    const double a0 = r.samples[0].area;
    for (const GrowthSample &g : r.samples)
        EXPECT_NEAR(g.area, a0 * (1 + 0.2 * g.time) * (1 + 0.05 * g.time), 1e-9 * a0)
            << g.time;
    RecordProperty("max_density_deviation", std::to_string(max_deviation(r)));
    expect_density_within(r, 0.10);
}

TEST(GrowingSimulation, DensityStaysConstantWhereOnlyHalfTheBodyGrows) {
    // The lower half of the cylinder (y < 0) triples its length over 8 time units, the
    // upper half keeps its size and rides on top (its pivot follows the lower half's
    // growth): each lower facet's area grows by L(t) = 1 + 0.25 t, the upper's stays.
    // Cells per unit area must stay constant in each half, not only overall.
    const std::string growth = R"({"cylinders": [
        {"name": "low", "from": [0, -1.0001, 0], "to": [0, 0, 0], "radius": 1.5},
        {"name": "up", "from": [0, 0, 0], "to": [0, 1.0001, 0], "radius": 1.5,
         "parent": "low"}],
        "keys": [{"age": 0, "cylinders": {}},
                 {"age": 8, "cylinders": {"low": {"length": 3}}}]})";
    const Surface s = build_surface("procedural:cylinder:48x16");
    const Preset p = parse_preset(growing_preset(growth, 8), "g.json");
    GrowingSurface growing(s.mesh, s.crps, resolve_growth(*p.growth, s.mesh, s.mesh));
    CmSimulation sim(growing.crps(), p.types, p.params, 3);
    sim.set_growth(&growing);
    sim.initialize();
    double area[2][2] = {{0, 0}, {0, 0}};  // [start, end][lower, upper]
    size_t cells[2][2] = {{0, 0}, {0, 0}};
    auto count = [&](int when) {
        for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
            const int half = s.crps.to_3d(t, {0, 0}).y < 0 ? 0 : 1;  // rest centroid
            area[when][half] += growing.crps().frame(t).area;
            cells[when][half] += sim.cells().on(t).size();
        }
    };
    count(0);
    sim.run();
    count(1);
    RecordProperty("lost_cells", std::to_string(sim.stats().growth_lost_cells));
    RecordProperty("cells", std::to_string(cells[0][0]) + " " +
                                std::to_string(cells[0][1]) + " -> " +
                                std::to_string(cells[1][0]) + " " +
                                std::to_string(cells[1][1]));
    EXPECT_NEAR(area[1][0] / area[0][0], 3.0, 1e-9);
    EXPECT_NEAR(area[1][1] / area[0][1], 1.0, 1e-9);
    for (int half : {0, 1}) {
        const double d0 = cells[0][half] / area[0][half],
                     d1 = cells[1][half] / area[1][half];
        RecordProperty(half ? "upper_density_ratio" : "lower_density_ratio",
                       std::to_string(d1 / d0));
        EXPECT_NEAR(d1 / d0, 1.0, 0.10) << (half ? "upper" : "lower") << ": "
                                        << cells[0][half] << " -> " << cells[1][half];
    }
    EXPECT_GT(cells[1][0], 2 * cells[0][0]);  // the growing half gained the cells
}

TEST(GrowingSimulation, IdenticalAtOneAndTwoThreads) {
    const std::string growth =
        R"({"keys": [{"age": 0, "scale": 0.6}, {"age": 2, "scale": 0.8}, {"age": 4, "scale": 1}],
           "interpolation": "smooth", "interval": 0.5})";
    std::vector<uint8_t> bytes[2];
    for (int threads : {1, 2}) {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
        bytes[threads - 1] = run_growing("procedural:sphere:20x20", growth, 4).bytes;
    }
    EXPECT_FALSE(bytes[0].empty());
    EXPECT_TRUE(bytes[0] == bytes[1]);
}

TEST(GrowingSurface, CellsKeepTheirBarycentricPointsAcrossAReshape) {
    const Surface s = build_surface("procedural:sphere:16x16");
    // A non-uniform change: x stretched ×3 at age 1, and a shear.
    std::vector<Vec3d> grown = s.mesh.positions;
    for (Vec3d &p : grown) p = {3 * p.x + 0.5 * p.y, p.y, p.z};
    GrowingSurface g(
        s.mesh, s.crps,
        GrowthShape({0, 1}, {s.mesh.positions, grown}, GrowthInterpolation::linear, 1));
    Cells cells(s.mesh.num_triangles());
    std::vector<Vec3d> bary;
    for (TriId t = 0; t < s.mesh.num_triangles(); t += 3) {
        const Vec3d b{0.2, 0.3 + 0.001 * (t % 100), 0.5 - 0.001 * (t % 100)};
        bary.push_back(b);
        cells.add({t, s.crps.barycentric_to_2d(t, b)}, 0);
    }
    g.reshape(1, cells);
    for (CellId c = 0; c < cells.size(); ++c) {
        const TriId t = cells.tri(c);
        const Vec3d b = g.crps().to_barycentric(t, cells.pos(c));
        EXPECT_NEAR(b.x, bary[c].x, 1e-12);
        EXPECT_NEAR(b.y, bary[c].y, 1e-12);
        // In 3D: the barycentric combination of the grown corners.
        const Vec3d want = grown[s.mesh.triangles[t][0]] * bary[c].x +
                           grown[s.mesh.triangles[t][1]] * bary[c].y +
                           grown[s.mesh.triangles[t][2]] * bary[c].z;
        EXPECT_LT(length(g.crps().to_3d(t, cells.pos(c)) - want), 1e-12);
        // The bucket still lists it.
        EXPECT_NE(std::find(cells.on(t).begin(), cells.on(t).end(), c),
                  cells.on(t).end());
    }
    EXPECT_EQ(g.crps().num_triangles(), s.crps.num_triangles());
}

TEST(GrowthDivisions, WaltersWorkedExample) {
    // Thesis L1502–1516: one polygon, ΔA = 0.05, a = 0.004, N_F = 10, N_B = 40, F splits
    // three times as fast: ΔN_F ≈ 5.357, ΔN_B ≈ 7.143 (r_F = 10/5.357 ≈ 1.867).
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}};
    const Surface s = build_surface(m);
    const Preset p = parse_preset(
        growing_preset(R"({"keys": [{"age": 0, "scale": 1}]})", 1), "g.json");
    Cells cells(1);
    for (int i = 0; i < 50; ++i)
        cells.add({0, s.crps.barycentric_to_2d(0, {0.2, 0.3, 0.5})}, i < 10 ? 0 : 1);
    double lost = -1;
    const std::vector<double> e =
        growth_divisions(s.crps, cells, p.types, {0.5}, {0.55}, 0.004, &lost);
    double f = 0, b = 0;
    for (CellId c = 0; c < 50; ++c) (c < 10 ? f : b) += e[c];
    EXPECT_NEAR(f, 5.357, 1e-3);
    EXPECT_NEAR(b, 7.143, 1e-3);
    EXPECT_NEAR(10 / f, 1.867, 1e-3);
    EXPECT_EQ(lost, 0);
    // Shrinking: no division.
    const std::vector<double> none =
        growth_divisions(s.crps, cells, p.types, {0.5}, {0.45}, 0.004, &lost);
    for (double x : none) EXPECT_EQ(x, 0);
}

}  // namespace
}  // namespace pelage::sim
