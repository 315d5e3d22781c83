// `pelage stats --mesh` on a pattern grown with a neural-crest mask: the masked-out share
// of the surface against Archimedes' zone area, and the share of it the masked type
// covers (cells never stand there; only their Voronoi regions reach over the edge).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/mesh/procedural_mesh.h"
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

// A dense PLY whose vertex property "paint" marks the x > 0 half: the run simulates on a
// simplified copy (no attributes), the mask is carried over from the input by closest
// points, and the masked type stays out of the other half.
TEST(MaskAdherence, PlyAttributeMaskSurvivesTheSimplifiedSurface) {
    TempDir tmp;
    const sim::TriangleMesh sphere = sim::make_icosphere(6);
    std::ostringstream ply;
    ply << "ply\nformat ascii 1.0\nelement vertex " << sphere.num_vertices()
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float paint"
           "\nelement face "
        << sphere.num_triangles()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    ply.precision(17);
    for (const sim::Vec3d &p : sphere.positions)
        ply << p.x << " " << p.y << " " << p.z << " " << (p.x > 0 ? 1 : 0) << "\n";
    for (const auto &t : sphere.triangles)
        ply << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    const std::string mesh = tmp.write("painted.ply", ply.str());
    const std::string preset = tmp.write("painted.json", R"({"name": "painted",
      "regions": {"painted": {"attribute": "paint"}},
      "masks": [{"type": "F", "only_in": "painted", "otherwise": "B"}],
      "types": [{"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": 3, "initial_probability": 0.5},
                {"name": "B", "colour": [0.9, 0.9, 0.9], "division_time": 6, "initial_probability": 0.5}],
      "adhesion": [[0.8, 0.0], [0.0, 0.5]],
      "simulation": {"initial_cells": 2000, "w_r": 2.5, "w_d": 0.1, "rho": 3, "end_time": 3}})");
    std::string out, err;
    ASSERT_EQ(run_pelage("sim --mesh " + mesh + " --preset " + preset + " -q -o " +
                             tmp.file("p.cells") + " --stats-json " + tmp.file("s.json"),
                         &out, &err),
              0)
        << err;
    const auto run = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    EXPECT_TRUE(run["simplified"].get<bool>());
    EXPECT_LT(run["triangles"].get<size_t>(), sphere.num_triangles() / 4);
    ASSERT_EQ(run_pelage("stats " + tmp.file("p.cells") + " --mesh " + mesh + " --json",
                         &out, &err),
              0)
        << err;
    const auto j = nlohmann::json::parse(out);
    ASSERT_TRUE(j.contains("mask_adherence")) << out;
    const auto &m = j["mask_adherence"][0];
    // Half the sphere, less the band of triangles that cross x = 0.
    EXPECT_GT(m["masked_out_share"].get<double>(), 0.45);
    EXPECT_LT(m["masked_out_share"].get<double>(), 0.5);
    EXPECT_LT(m["violation"].get<double>(), 0.05);
    EXPECT_GT(j["area_fraction_by_type"]["F"].get<double>(), 0.15);
}

}  // namespace
}  // namespace pelage::test
