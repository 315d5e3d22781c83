// `pelage compare` end to end on a tiny scene: every shader rendered, the report's keys
// (a contract), a contact sheet, and exit 2 for a scene with nothing to compare.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::string scene_json(const std::string &cells) {
    return R"({"camera": {"type": "pinhole", "position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 32, "height": 24, "spp": 2},
      "lights": [{"type": "environment", "color": [1, 1, 1]}],
      "objects": [{"mesh": "procedural:icosphere:3", )" +
           (cells.empty() ? std::string() : "\"cells\": \"" + cells + "\", ") +
           R"("material": {"shader": ")" + (cells.empty() ? "diffuse" : "clonal_mosaic") +
           R"("}}]})";
}

TEST(CompareCli, ReportsEveryShaderAndWritesASheet) {
    TempDir tmp;
    const std::string scene = tmp.write(
        "scene.json",
        scene_json(simulate_two_type_cells(tmp, "procedural:icosphere:3", 300)));
    std::string err;
    ASSERT_EQ(
        run_pelage("compare " + scene + " --lookups 1000 --atlas-res 256 --stats-json " +
                       tmp.file("r.json") + " --sheet " + tmp.file("sheet.png"),
                   nullptr, &err),
        0)
        << err;
    const auto r = nlohmann::json::parse(std::ifstream(tmp.file("r.json")));
    for (const char *s : {"clonal_mosaic", "worley", "perlin", "texture", "diffuse"}) {
        ASSERT_TRUE(r["shaders"].contains(s)) << s;
        EXPECT_GT(r["shaders"][s]["seconds"].get<double>(), 0.0);
        EXPECT_GT(r["shaders"][s]["ns_per_lookup"].get<double>(), 0.0);
    }
    for (const char *k : {"clonal_mosaic_vs_worley", "clonal_mosaic_vs_perlin",
                          "clonal_mosaic_vs_diffuse"})
        EXPECT_GT(r["ratios"][k].get<double>(), 0.0) << k;
    EXPECT_GT(r["lookup_ratios"]["clonal_mosaic_vs_worley"].get<double>(), 0.0);
    EXPECT_GT(std::filesystem::file_size(tmp.file("sheet.png")), 1000u);
}

// Fairness: worley and perlin take the mosaic's colours and spot fraction, and texture
// renders the mosaic's baked atlas, so all four show the same coat.
TEST(CompareCli, BaselinesMatchTheMosaicAndTextureUsesItsAtlas) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, "procedural:icosphere:3", 300);
    const std::string scene = tmp.write("scene.json", scene_json(cells));
    std::string out, err;
    ASSERT_EQ(run_pelage("compare " + scene +
                             " --shaders clonal_mosaic,worley,perlin,texture --lookups "
                             "1000 --atlas-res 256 --stats-json " +
                             tmp.file("r.json"),
                         &out, &err),
              0)
        << err;
    const auto r = nlohmann::json::parse(std::ifstream(tmp.file("r.json")));
    ASSERT_TRUE(r["shaders"].contains("texture"));
    EXPECT_GT(r["shaders"]["texture"]["ns_per_lookup"].get<double>(), 0.0);
    const auto &w = r["params"]["worley"], &p = r["params"]["perlin"];
    // The two-type preset's colours, spot first; the same for both baselines.
    EXPECT_EQ(w["spot_colour"], p["spot_colour"]);
    EXPECT_EQ(w["base_colour"], p["base_colour"]);
    EXPECT_NE(w["spot_colour"], w["base_colour"]);
    const double f = w["spot_fraction"].get<double>();
    EXPECT_GT(f, 0.0);
    EXPECT_LT(f, 1.0);
    EXPECT_GT(w["frequency"].get<double>(), 0.0);
    EXPECT_TRUE(p.contains("threshold"));
    EXPECT_TRUE(r["params"]["texture"].contains("file"));
    EXPECT_NE(out.find("baked the mosaic"), std::string::npos) << out;
    // The atlas lived in a temporary directory, removed afterwards.
    EXPECT_FALSE(
        std::filesystem::exists(r["params"]["texture"]["file"].get<std::string>()));
    // --no-match: the plugins' defaults (no params given).
    ASSERT_EQ(
        run_pelage(
            "compare " + scene +
            " --shaders clonal_mosaic,worley --lookups 1000 --no-match --stats-json " +
            tmp.file("d.json")),
        0);
    const auto d = nlohmann::json::parse(std::ifstream(tmp.file("d.json")));
    EXPECT_TRUE(d["params"]["worley"].empty());
}

// --repeat: every shader rendered N times; the time reported is the minimum of the N,
// which the report lists; the images do not depend on it.
TEST(CompareCli, RepeatReportsTheMinimumOfEveryRender) {
    TempDir tmp;
    const std::string scene = tmp.write(
        "scene.json",
        scene_json(simulate_two_type_cells(tmp, "procedural:icosphere:3", 300)));
    std::string err;
    ASSERT_EQ(run_pelage("compare " + scene +
                             " --shaders clonal_mosaic,diffuse --lookups 1000 --repeat 3 "
                             "--stats-json " +
                             tmp.file("r.json"),
                         nullptr, &err),
              0)
        << err;
    const auto r = nlohmann::json::parse(std::ifstream(tmp.file("r.json")));
    EXPECT_EQ(r["repeats"].get<int>(), 3);
    for (const char *s : {"clonal_mosaic", "diffuse"}) {
        const auto &each = r["shaders"][s]["cpu_seconds_each"];
        ASSERT_EQ(each.size(), 3u) << s;
        double lo = each[0].get<double>();
        for (const auto &v : each) lo = std::min(lo, v.get<double>());
        EXPECT_EQ(r["shaders"][s]["cpu_seconds"].get<double>(), lo) << s;
    }
    const double ratio = r["ratios"]["clonal_mosaic_vs_diffuse"].get<double>();
    EXPECT_NEAR(ratio,
                r["shaders"]["clonal_mosaic"]["cpu_seconds"].get<double>() /
                    r["shaders"]["diffuse"]["cpu_seconds"].get<double>(),
                1e-12);
    // Round by round: the paired ratios' range, which holds the ratio of the minima.
    const auto &rounds = r["ratio_rounds"]["clonal_mosaic_vs_diffuse"];
    const auto &cm = r["shaders"]["clonal_mosaic"]["cpu_seconds_each"];
    const auto &df = r["shaders"]["diffuse"]["cpu_seconds_each"];
    std::vector<double> paired;
    for (size_t k = 0; k < 3; ++k)
        paired.push_back(cm[k].get<double>() / df[k].get<double>());
    std::sort(paired.begin(), paired.end());
    EXPECT_EQ(rounds["min"].get<double>(), paired[0]);
    EXPECT_EQ(rounds["median"].get<double>(), paired[1]);
    EXPECT_EQ(rounds["max"].get<double>(), paired[2]);
    EXPECT_LE(rounds["min"].get<double>(), ratio * (1 + 1e-12));
    EXPECT_GE(rounds["max"].get<double>(), ratio * (1 - 1e-12));
    EXPECT_EQ(run_pelage("compare " + scene + " --repeat 0", nullptr, &err), 2);
    EXPECT_NE(err.find("--repeat"), std::string::npos) << err;
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
