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

std::string patterned_scene(int seed) {
    return R"({"camera": {"position": [0, 0, 4]},
      "film": {"width": 16, "height": 12, "spp": 1, "output": "out.exr",
               "preview": "out_preview.png"},
      "objects": [{"mesh": "procedural:sphere:12x12", "cells": "coat.cells",
                   "pattern": {"preset": "two_types.json", "seed": )" +
           std::to_string(seed) + R"(},
                   "material": {"shader": "clonal_mosaic"}}]})";
}

TEST(ScenePaths, PatternIsGrownOnceAndAgainWhenItsRecipeChanges) {
    TempDir tmp;
    two_type_preset(tmp, 300);
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
                             tmp.file("two_types.json") + " --seed 3 -o " + by_sim,
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
    two_type_preset(tmp, 200);
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
    two_type_preset(tmp, 300);
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
    two_type_preset(tmp, 300);
    std::string out, err;
    ASSERT_EQ(run_pelage("sim --mesh procedural:sphere:8x8 --preset " +
                             tmp.file("two_types.json"),
                         &out, &err),
              0);
    EXPECT_NE(err.find("no -o given, the cells will not be saved"), std::string::npos)
        << err;
}

}  // namespace
}  // namespace pelage::test
