// The anisotropy field as a run uses it (sim/mosaic/anisotropy_field.h): a preset's
// "field" reaches the relaxation, and its constant form is the world direction.
#include "sim/mosaic/anisotropy_field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/crps/surface.h"
#include "sim/field/vector_heat.h"
#include "sim/mesh/procedural_mesh.h"
#include "sim/mosaic/cm_simulation.h"
#include "sim/mosaic/preset.h"
#include "tests/sim/sim_test_util.h"

namespace pelage::sim {
namespace {

Preset preset_with(const std::string &anisotropy, double w_a) {
    return parse_preset(
        test::preset_json(R"({"initial_cells": 600, "w_r": 2.0, "w_d": 0.5,
        "w_a": )" + std::to_string(w_a) +
                              R"(, "anisotropy": )" + anisotropy +
                              R"(, "rho": 4, "end_time": 2})",
                          true, "1"),
        "p.json");
}

TEST(AnisotropyField, AConstantFieldGrowsTheSameCellsAsTheWorldDirection) {
    const Surface s = build_surface(make_icosphere(3));
    const Preset a = preset_with(R"({"direction": [0, 1, 1]})", 0.7);
    const Preset b = preset_with(R"({"field": {"direction": [0, 1, 1]}})", 0.7);
    CmSimulation sa(s.crps, a.types, a.params, 5), sb(s.crps, b.types, b.params, 5);
    sa.initialize();
    sb.initialize();
    sa.run();
    sb.run();
    ASSERT_EQ(sa.cells().size(), sb.cells().size());
    for (CellId c = 0; c < sa.cells().size(); ++c) {
        ASSERT_EQ(sa.cells().tri(c), sb.cells().tri(c));
        ASSERT_EQ(sa.cells().pos(c), sb.cells().pos(c));
    }
}

TEST(AnisotropyField, WithFullAnisotropyCellsMoveOnlyAlongTheField) {
    // On a cylinder, "around" the body axis: with w_a = 1 the relaxation moves every
    // cell along its own triangle's vector, i.e. around the axis, never along it.
    const Surface s = build_surface(make_cylinder(48, 40, 1.0, 5.0));
    const Preset p = preset_with(R"({"field": {"around": "body_axis"}})", 1.0);
    const TangentField f = anisotropy_field(p.params, s.crps);
    CmSimulation sim(s.crps, p.types, p.params, 9);
    sim.initialize();
    std::vector<Vec3d> before;
    for (CellId c = 0; c < sim.cells().size(); ++c)
        before.push_back(s.crps.to_3d(sim.cells().tri(c), sim.cells().pos(c)));
    std::vector<TriId> all(s.crps.num_triangles());
    for (TriId t = 0; t < all.size(); ++t) all[t] = t;
    sim.relax(all, false);
    size_t moved = 0;
    for (CellId c = 0; c < sim.cells().size(); ++c) {
        const Vec3d after = s.crps.to_3d(sim.cells().tri(c), sim.cells().pos(c));
        if (length(after - before[c]) < 1e-9) continue;
        ++moved;
        EXPECT_NEAR(after.y, before[c].y, 1e-9) << c;  // Y is the axis
    }
    EXPECT_GT(moved, sim.cells().size() / 2);
    for (TriId t = 0; t < s.crps.num_triangles(); ++t)
        EXPECT_NEAR(std::abs(field_to_world(s.crps, t, f.a[t]).y), 0.0, 1e-9);
}

}  // namespace
}  // namespace pelage::sim
