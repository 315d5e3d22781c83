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
    const std::string scene = tmp.write("scene.json", scene_json(simulate_two_type_cells(tmp, "procedural:icosphere:3", 300)));
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
