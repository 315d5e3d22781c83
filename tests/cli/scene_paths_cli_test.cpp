// Scenes that move with their files: a pattern grown into the object's cells on first
// use and reused after, the preview beside -o, and `pelage sim` saying when it saves
// nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/cells_io/cells_file.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

const char *quick_preset = R"({"name": "quick", "types": [
    {"name": "F", "colour": [0.1, 0.05, 0.02], "eumelanin": 0.8, "division_time": "never",
     "initial_probability": 0.3},
    {"name": "B", "colour": [0.9, 0.6, 0.3], "pheomelanin": 0.5, "division_time": "never",
     "initial_probability": 0.7}],
    "adhesion": [[0.5, 0.0], [0.0, 0.5]],
    "simulation": {"initial_cells": 300, "initial_relax_steps": 5,
                   "w_r": 2.0, "w_d": 0.1, "rho": 5, "end_time": 1, "relax": "global"}})";

std::string patterned_scene(int seed) {
    return R"({"camera": {"position": [0, 0, 4]},
      "film": {"width": 16, "height": 12, "spp": 1, "output": "out.exr",
               "preview": "out_preview.png"},
      "objects": [{"mesh": "procedural:sphere:12x12", "cells": "coat.cells",
                   "pattern": {"preset": "quick.json", "seed": )" +
           std::to_string(seed) + R"(},
                   "material": {"shader": "clonal_mosaic"}}]})";
}

TEST(ScenePaths, PatternIsGrownOnceAndAgainWhenItsRecipeChanges) {
    TempDir tmp;
    tmp.write("quick.json", quick_preset);
    const std::string scene = tmp.write("s.json", patterned_scene(3));
    std::string out, err;
    ASSERT_EQ(run_pelage("render " + scene, &out, &err), 0) << err;
    EXPECT_NE(err.find("no file, growing"), std::string::npos) << err;
    ASSERT_TRUE(fs::exists(tmp.file("coat.cells")));
    EXPECT_TRUE(fs::exists(tmp.file("out.exr")));
    const auto first_time = fs::last_write_time(tmp.file("coat.cells"));

    ASSERT_EQ(run_pelage("render " + scene, &out, &err), 0) << err;
    EXPECT_EQ(err.find("growing"), std::string::npos) << err;
    EXPECT_EQ(fs::last_write_time(tmp.file("coat.cells")), first_time);

    // The same cells as `pelage sim` grows from that preset and seed: the render's
    // growth is the simulation, not an approximation of it.
    const std::string by_sim = tmp.file("by_sim.cells");
    ASSERT_EQ(run_pelage("sim --mesh procedural:sphere:12x12 --preset " +
                             tmp.file("quick.json") + " --seed 3 -o " + by_sim,
                         nullptr, &err),
              0)
        << err;
    const sim::CellsData a = sim::read_cells_file(tmp.file("coat.cells")),
                         b = sim::read_cells_file(by_sim);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.z, b.z);
    EXPECT_EQ(a.type, b.type);

    // Another seed: grown again.
    tmp.write("s.json", patterned_scene(4));
    ASSERT_EQ(run_pelage("render " + scene, &out, &err), 0) << err;
    EXPECT_NE(err.find("grown with another seed, growing"), std::string::npos) << err;
    EXPECT_NE(sim::read_cells_file(tmp.file("coat.cells")).x, b.x);

    // A file from `pelage sim` with the scene's recipe is used as it is.
    fs::copy_file(by_sim, tmp.file("coat.cells"), fs::copy_options::overwrite_existing);
    tmp.write("s.json", patterned_scene(3));
    ASSERT_EQ(run_pelage("render " + scene, &out, &err), 0) << err;
    EXPECT_EQ(err.find("growing"), std::string::npos) << err;

    // Another preset (by content, not by name): grown again.
    std::string edited = quick_preset;
    edited.replace(edited.find("\"initial_cells\": 300"), 20, "\"initial_cells\": 200");
    tmp.write("quick.json", edited);
    ASSERT_EQ(run_pelage("render " + scene, &out, &err), 0) << err;
    EXPECT_NE(err.find("grown from another preset, growing"), std::string::npos) << err;
}

TEST(ScenePaths, PatternWithoutCellsIsRefused) {
    TempDir tmp;
    const std::string scene = tmp.write(
        "s.json", R"({"camera": {}, "objects": [{"mesh": "procedural:sphere:8x8",
        "pattern": {"preset": "teo-cheetah"}, "material": {"shader": "clonal_mosaic"}}]})");
    std::string err;
    EXPECT_EQ(run_pelage("render " + scene + " -o " + tmp.file("o.exr"), nullptr, &err),
              2);
    EXPECT_NE(err.find("objects[0].pattern"), std::string::npos) << err;
    EXPECT_NE(err.find("needs \"cells\""), std::string::npos) << err;
}

TEST(ScenePaths, PreviewGoesBesideTheOutputGiven) {
    TempDir tmp;
    tmp.write("quick.json", quick_preset);
    const std::string scene = tmp.write("s.json", patterned_scene(3));
    fs::create_directory(tmp.file("elsewhere"));
    std::string err;
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + tmp.file("elsewhere/shot.exr"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_TRUE(fs::exists(tmp.file("elsewhere/shot.exr")));
    EXPECT_TRUE(fs::exists(tmp.file("elsewhere/shot_preview.png")));
    EXPECT_FALSE(fs::exists(tmp.file("out_preview.png")));
    EXPECT_FALSE(fs::exists(tmp.file("out.exr")));
}

TEST(ScenePaths, SimWithoutOutputSaysSoBeforeItRuns) {
    TempDir tmp;
    tmp.write("quick.json", quick_preset);
    std::string out, err;
    ASSERT_EQ(
        run_pelage("sim --mesh procedural:sphere:8x8 --preset " + tmp.file("quick.json"),
                   &out, &err),
        0);
    EXPECT_NE(err.find("no -o given, the cells will not be saved"), std::string::npos)
        << err;
}

}  // namespace
}  // namespace pelage::test
