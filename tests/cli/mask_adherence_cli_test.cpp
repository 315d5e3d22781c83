// `pelage stats --mesh` on a pattern grown with a neural-crest mask: the masked-out share
// of the surface against Archimedes' zone area, and the share of it the masked type
// covers (cells never stand there; only their Voronoi regions reach over the edge).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(MaskAdherence, StatsReportsTheMaskedOutAreaAndWhatCoversIt) {
    TempDir tmp;
    // F only above 0.6 of the height of the unit sphere (y > 0.2), hard-edged.
    const std::string preset = tmp.write("masked.json", R"({"name": "masked",
      "regions": {"cap": {"height": {"above": 0.6}}},
      "masks": [{"type": "F", "only_in": "cap", "otherwise": "B"}],
      "types": [{"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": 3, "initial_probability": 0.5},
                {"name": "B", "colour": [0.9, 0.9, 0.9], "division_time": 6, "initial_probability": 0.5}],
      "adhesion": [[0.8, 0.0], [0.0, 0.5]],
      "simulation": {"initial_cells": 1500, "w_r": 2.5, "w_d": 0.1, "rho": 5, "end_time": 6}})");
    const std::string mesh = "procedural:sphere:40x40";
    ASSERT_EQ(run_pelage("sim --mesh " + mesh + " --preset " + preset + " -q -o " +
                         tmp.file("m.cells")),
              0);
    std::string out, err;
    ASSERT_EQ(run_pelage("stats " + tmp.file("m.cells") + " --mesh " + mesh + " --json",
                         &out, &err),
              0)
        << err;
    const auto j = nlohmann::json::parse(out);
    ASSERT_TRUE(j.contains("mask_adherence")) << out;
    ASSERT_EQ(j["mask_adherence"].size(), 1u);
    const auto &m = j["mask_adherence"][0];
    EXPECT_EQ(m["type"], "F");
    EXPECT_EQ(m["only_in"], "cap");
    // The zone y < 0.2 holds (1 + 0.2) / 2 = 60 % of a sphere's area; the mask is 0 on
    // the triangles wholly inside it, one ring (1/40 of the height) less.
    EXPECT_GT(m["masked_out_share"].get<double>(), 0.6 - 0.05);
    EXPECT_LT(m["masked_out_share"].get<double>(), 0.6);
    // F cells stand only where m > 0: their regions reach at most a cell spacing into
    // the masked-out zone, a thin band of its area.
    EXPECT_LT(m["violation"].get<double>(), 0.05);
    EXPECT_GT(j["area_fraction_by_type"]["F"].get<double>(), 0.2);
}

}  // namespace
}  // namespace pelage::test
