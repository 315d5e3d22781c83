// `pelage compare` end to end on a tiny scene: every shader rendered, the report's keys
// (a contract), a contact sheet, and exit 2 for a scene with nothing to compare.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::string scene_json(const std::string &cells) {
    return R"({"camera": {"type": "pinhole", "position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 32, "height": 24, "spp": 2},
      "lights": [{"type": "environment", "color": [1, 1, 1]}],
      "objects": [{"mesh": "procedural:icosphere:3", )" +
           (cells.empty() ? std::string() : "\"cells\": \"" + cells + "\", ") +
           R"("material": {"shader": ")" + (cells.empty() ? "diffuse" : "clonal_mosaic") + R"("}}]})";
}

TEST(CompareCli, ReportsEveryShaderAndWritesASheet) {
    TempDir tmp;
    const std::string preset = tmp.write("p.json", R"({"name": "t", "types": [
        {"name": "F", "colour": [0.1, 0.05, 0.02], "division_time": "never", "initial_probability": 0.3},
        {"name": "B", "colour": [0.9, 0.6, 0.3], "division_time": "never", "initial_probability": 0.7}],
        "adhesion": [[0.5, 0.0], [0.0, 0.5]],
        "simulation": {"initial_cells": 300, "initial_relax_steps": 5, "w_r": 2.0, "w_d": 0.1,
                       "rho": 2, "end_time": 1, "relax": "global"}})");
    ASSERT_EQ(run_pelage("sim --mesh procedural:icosphere:3 --preset " + preset + " -o " + tmp.file("s.cells")), 0);
    const std::string scene = tmp.write("scene.json", scene_json(tmp.file("s.cells")));
    std::string err;
    ASSERT_EQ(run_pelage("compare " + scene + " --lookups 1000 --report " + tmp.file("r.json") + " --sheet " +
                             tmp.file("sheet.png"), nullptr, &err),
              0)
        << err;
    const auto r = nlohmann::json::parse(std::ifstream(tmp.file("r.json")));
    for (const char *s : {"clonal_mosaic", "worley", "perlin", "diffuse"}) {
        ASSERT_TRUE(r["shaders"].contains(s)) << s;
        EXPECT_GT(r["shaders"][s]["seconds"].get<double>(), 0.0);
        EXPECT_GT(r["shaders"][s]["ns_per_lookup"].get<double>(), 0.0);
    }
    for (const char *k : {"clonal_mosaic_vs_worley", "clonal_mosaic_vs_perlin", "clonal_mosaic_vs_diffuse"})
        EXPECT_GT(r["ratios"][k].get<double>(), 0.0) << k;
    EXPECT_GT(r["lookup_ratios"]["clonal_mosaic_vs_worley"].get<double>(), 0.0);
    EXPECT_GT(std::filesystem::file_size(tmp.file("sheet.png")), 1000u);
}

TEST(CompareCli, SceneWithoutPatternIsExit2) {
    TempDir tmp;
    const std::string scene = tmp.write("scene.json", scene_json(""));
    std::string err;
    EXPECT_EQ(run_pelage("compare " + scene, nullptr, &err), 2);
    EXPECT_NE(err.find("patterned"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
