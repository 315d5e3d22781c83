// Anisotropy fields through the command line: a bad field (in the preset, or one that
// cannot be resolved on the mesh) is exit 2 naming its JSON path with nothing written,
// and `pelage stats` measures the stripes of cells grown with a field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"
#include "sim/run/cells_data.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::string field_preset(const TempDir &tmp, const std::string &field) {
    const std::string path = tmp.file("field.json");
    std::ofstream(path) << R"({"name": "field", "types": [
        {"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": 2, "initial_probability": 0.3},
        {"name": "B", "colour": [0.9, 0.8, 0.7], "division_time": 6, "initial_probability": 0.7}],
      "adhesion": [[0.5, 0], [0, 0.5]],
      "simulation": {"initial_cells": 500, "w_r": 2.4, "w_d": 1, "w_a": 0.9,
        "anisotropy": {"field": )" +
                               field + R"(}, "rho": 6, "end_time": 4}})";
    return path;
}

TEST(FieldCli, BadFieldsExitWithTwoNamingTheJsonPath) {
    TempDir tmp;
    const std::string cells = tmp.file("out.cells");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"around": "spine"})", "simulation.anisotropy.field.around"},
        {R"({"controls": [{"at": [0, 0, 0], "direction": [0, 1, 0]}], "space": "world"})",
         "simulation.anisotropy.field.controls[0].direction"},  // normal to the plane
    };
    for (const auto &[field, path] : cases) {
        std::string err;
        EXPECT_EQ(run_pelage("sim --mesh procedural:plane:8x8 --preset " +
                                 field_preset(tmp, field) + " -o " + cells + " -q",
                             nullptr, &err),
                  2)
            << field;
        EXPECT_NE(err.find(path), std::string::npos) << err;
        EXPECT_FALSE(std::filesystem::exists(cells));
    }
}

TEST(FieldCli, StatsMeasureTheStripesAgainstTheField) {
    TempDir tmp;
    const std::string cells = tmp.file("out.cells");
    ASSERT_EQ(run_pelage("sim --mesh procedural:cylinder:48x24 --preset " +
                         field_preset(tmp, R"({"around": "body_axis"})") + " -o " +
                         cells + " -q"),
              0);
    std::string out;
    ASSERT_EQ(run_pelage("stats " + cells + " --json", &out), 0);
    const auto j = nlohmann::json::parse(out);
    ASSERT_TRUE(j.contains("stripe_alignment_median")) << out;
    EXPECT_GT(j["stripe_alignment_samples"].get<size_t>(), 50u);
    EXPECT_LE(j["stripe_alignment_q1"].get<double>(),
              j["stripe_alignment_median"].get<double>());
    EXPECT_LE(j["stripe_alignment_median"].get<double>(),
              j["stripe_alignment_q3"].get<double>());
    EXPECT_LE(j["stripe_alignment_q3"].get<double>(), 90.0);
    // Without anisotropy there is no field to measure against.
    const std::string plain =
        simulate_two_type_cells(tmp, "procedural:sphere:20x20", 300);
    ASSERT_EQ(run_pelage("stats " + plain + " --json", &out), 0);
    EXPECT_FALSE(nlohmann::json::parse(out).contains("stripe_alignment_median"));
}

TEST(FieldCli, StatsOfAFileWhosePresetNoLongerParsesSkipOnlyTheAlignment) {
    TempDir tmp;
    const sim::Surface s = sim::build_surface("procedural:sphere:8x8");
    sim::CellType f, b;
    f.name = "F";
    b.name = "B";
    sim::Cells cells(s.crps.num_triangles());
    cells.add({0, {0, 0}}, 0);
    cells.add({1, {0, 0}}, 1);
    const std::string path = tmp.file("old.cells");
    sim::write_cells_file(
        path,
        sim::make_cells_data(s.mesh, s.crps,
                             sim::CellTypes({f, b}, {{1, 0}, {0, 1}}, {{0, 0}, {0, 0}}),
                             cells, R"({"preset": {"name": "old", "shape": 3}})", 1));
    std::string out, err;
    ASSERT_EQ(run_pelage("stats " + path + " --json", &out, &err), 0) << err;
    EXPECT_NE(err.find("no stripe alignment"), std::string::npos) << err;
    EXPECT_EQ(nlohmann::json::parse(out)["cells"].get<size_t>(), 2u);
}

}  // namespace
}  // namespace pelage::test
