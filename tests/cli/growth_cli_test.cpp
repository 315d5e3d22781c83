// Growth end to end: `pelage sim` on a growing surface reports cells per unit area at
// every reshape (within 10 % of the start) and writes the cells on the rest mesh; a bad
// growth block or a pose of another topology is exit 2 naming the JSON path, with
// nothing written; a scene's "grow" renders, and its errors are exit 2.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::string growing_preset(const TempDir &tmp, const std::string &growth) {
    return tmp.write("growing.json", R"({"name": "growing", "types": [
      {"name": "F", "colour": [0.1, 0.05, 0.02], "division_time": 4, "initial_probability": 0.3},
      {"name": "B", "colour": [0.9, 0.6, 0.3], "division_time": 12, "initial_probability": 0.7}],
      "adhesion": [[0.8, 0.0], [0.0, 0.4]],
      "simulation": {"initial_cells": 600, "w_r": 2.0, "w_d": 0.1, "rho": 6, "end_time": 0,
                     "division_distribution": "exponential"},
      "growth": )" + growth + "}");
}

TEST(GrowthCli, DensityPerReshapeInStatsJson) {
    TempDir tmp;
    const std::string preset = growing_preset(
        tmp,
        R"({"keys": [{"age": 0, "scale": 0.5}, {"age": 6, "scale": 1}], "interval": 1})");
    std::string err;
    ASSERT_EQ(
        run_pelage("sim --mesh procedural:sphere:20x20 --preset " + preset + " -o " +
                       tmp.file("g.cells") + " --stats-json " + tmp.file("s.json"),
                   nullptr, &err),
        0)
        << err;
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    ASSERT_EQ(s["growth"].size(), 7u);  // t = 0 … 5, and the end at 6
    const double d0 = s["growth"][0]["density"];
    for (const auto &g : s["growth"])
        EXPECT_NEAR(g["density"].get<double>() / d0, 1.0, 0.10) << g.dump();
    EXPECT_NEAR(
        s["growth"][6]["area"].get<double>() / s["growth"][0]["area"].get<double>(), 4.0,
        1e-9);
    // The .cells file is on the rest sphere (area of the scale-1 shape).
    EXPECT_NEAR(s["area"].get<double>(), s["growth"][6]["area"].get<double>(), 1e-9);
    EXPECT_EQ(s["final_cells"], s["growth"][6]["cells"]);
    // The adult's spots, measured by `pelage stats` on the surface the file carries.
    std::string out;
    ASSERT_EQ(run_pelage("stats " + tmp.file("g.cells") + " --json", &out), 0);
    const auto st = nlohmann::json::parse(out);
    EXPECT_NEAR(st["area"].get<double>(), s["area"].get<double>(), 1e-12);
    for (const char *q : {"min", "q10", "median", "q90", "max"})
        EXPECT_TRUE(st["spot_area_quantiles"].contains(q)) << q;
    EXPECT_LE(st["spot_area_quantiles"]["median"].get<double>(),
              st["spot_area_quantiles"]["max"].get<double>());
    // No growth: an empty list.
    ASSERT_EQ(run_pelage("sim --mesh procedural:sphere:20x20 --preset teo-table-7.2 "
                         "--initial-cells 300 -q --stats-json " +
                         tmp.file("n.json")),
              0);
    EXPECT_TRUE(
        nlohmann::json::parse(std::ifstream(tmp.file("n.json")))["growth"].empty());
}

TEST(GrowthCli, PatternBeforeGrowthRunsOnTheFirstShapeAndWritesOnTheRest) {
    TempDir tmp;
    // Walter thesis §6.7: the types' own division times on the half-size sphere for 2
    // time units (F every 4 on average, B every 12), then carried to the rest sphere.
    const std::string preset = growing_preset(tmp, R"({"pattern": "before_growth",
                 "keys": [{"age": 0, "scale": 0.5}, {"age": 6, "scale": 1}]})");
    std::string text = slurp(preset);
    text.replace(text.find("\"end_time\": 0"), 13, "\"end_time\": 2");
    tmp.write("growing.json", text);
    std::string err;
    ASSERT_EQ(
        run_pelage("sim --mesh procedural:sphere:20x20 --preset " + preset + " -o " +
                       tmp.file("b.cells") + " --stats-json " + tmp.file("s.json"),
                   nullptr, &err),
        0)
        << err;
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    ASSERT_EQ(s["growth"].size(), 1u);  // the start only: no reshape
    EXPECT_NEAR(s["growth"][0]["area"].get<double>() / s["area"].get<double>(), 0.25,
                1e-9);
    EXPECT_EQ(s["end_time"], 2.0);
    // Divisions at the types' rates over 2 time units (not from the growth, which would
    // quadruple the 600 cells): about 600 (0.3·0.5 + 0.7·(2/12)) ≈ 160.
    const double divisions = s["divisions"];
    EXPECT_GT(divisions, 80);
    EXPECT_LT(divisions, 300);
    EXPECT_EQ(s["final_cells"].get<double>(), 600 + divisions);
}

TEST(GrowthCli, BadGrowthIsExitTwoNamingTheField) {
    TempDir tmp;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"keys": [{"age": 0}]})", "growth.keys[0]"},
        {R"({"keys": [{"age": 2, "scale": 1}, {"age": 1, "scale": 2}]})",
         "growth.keys[1].age"},
        {R"({"keys": [{"age": 0, "scale": 1}], "interpolation": "spline"})",
         "growth.interpolation"},
        {R"({"keys": [{"age": 0, "mesh": "missing.obj"}]})", "growth.keys[0].mesh"},
    };
    for (const auto &[growth, field] : cases) {
        const std::string preset = growing_preset(tmp, growth);
        std::string err;
        EXPECT_EQ(run_pelage("sim --mesh procedural:sphere:20x20 --preset " + preset +
                                 " -o " + tmp.file("bad.cells"),
                             nullptr, &err),
                  2)
            << growth;
        EXPECT_NE(err.find(field), std::string::npos) << err;
        EXPECT_FALSE(std::filesystem::exists(tmp.file("bad.cells")));
    }
}

TEST(GrowthCli, AMeshKeyOfAnotherTopologyIsNamed) {
    TempDir tmp;
    sim::write_obj(tmp.file("rest.obj"), sim::make_uv_sphere(10, 16), {});
    sim::write_obj(tmp.file("other.obj"), sim::make_uv_sphere(10, 18), {});
    const std::string preset = growing_preset(
        tmp, R"({"keys": [{"age": 0, "scale": 0.5}, {"age": 3, "mesh": "other.obj"}]})");
    std::string err;
    EXPECT_EQ(run_pelage("sim --mesh " + tmp.file("rest.obj") + " --preset " + preset +
                             " --surface input -o " + tmp.file("bad.cells"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("growth.keys[1].mesh"), std::string::npos) << err;
    EXPECT_NE(err.find("does not have the rest mesh's topology"), std::string::npos)
        << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("bad.cells")));
}

std::string grow_scene(const std::string &mesh, const std::string &grow) {
    return R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 24, "height": 24, "spp": 1, "output": "g.####.exr"},
      "lights": [{"type": "environment", "intensity": 1}],
      "objects": [{"name": "ball", "mesh": ")" +
           mesh + R"(", "cells": "g.cells",
        "pattern": {"preset": "growing.json", "seed": 1},
        "material": {"shader": "clonal_mosaic"}, "grow": )" +
           grow + R"(}],
      "animation": {"frames": 2}})";
}

TEST(GrowthCli, ASceneGrowsItsMeshAndRefusesBadGrow) {
    TempDir tmp;
    sim::write_obj(tmp.file("ball.obj"), sim::make_uv_sphere(10, 16), {});
    growing_preset(tmp,
                   R"({"keys": [{"age": 0, "scale": 0.5}, {"age": 2, "scale": 1}]})");
    const std::string scene =
        tmp.write("s.json", grow_scene("ball.obj", R"({"from": 0, "to": 2})"));
    std::string err;
    ASSERT_EQ(run_pelage("render " + scene + " --frames 0-1 -q", nullptr, &err), 0)
        << err;
    // The ball covers about 4× the pixels at scale 1 (last frame) as at 0.5 (first):
    // with the camera 4 radii away, (tan asin(1/4) / tan asin(1/8))² ≈ 4.2.
    double coverage[2];
    for (int f = 0; f < 2; ++f) {
        OIIO::ImageBuf image(tmp.file("g.000" + std::to_string(f) + ".exr"));
        ASSERT_TRUE(image.read()) << f;
        const int alpha = image.spec().channelindex("A");
        ASSERT_GE(alpha, 0);
        const auto stats = OIIO::ImageBufAlgo::computePixelStats(image);
        coverage[f] = stats.avg[alpha];
    }
    EXPECT_GT(coverage[0], 0);
    EXPECT_NEAR(coverage[1] / coverage[0], 4.2, 0.8);
    for (const auto &[grow, field] : std::vector<std::pair<std::string, std::string>>{
             {R"({"from": 0})", "objects[0].grow.to"},
             {R"({"from": 0, "to": 1, "speed": 2})", "objects[0].grow.speed"},
             {R"({"preset": "nowhere.json", "from": 0, "to": 1})", "nowhere.json"}}) {
        const std::string bad = tmp.write("bad.json", grow_scene("ball.obj", grow));
        EXPECT_EQ(run_pelage("render " + bad + " -q", nullptr, &err), 2) << grow;
        EXPECT_NE(err.find(field), std::string::npos) << err;
    }
    const std::string procedural = tmp.write(
        "p.json", grow_scene("procedural:sphere:8x8", R"({"from": 0, "to": 1})"));
    EXPECT_EQ(run_pelage("render " + procedural + " -q", nullptr, &err), 2);
    EXPECT_NE(err.find("objects[0].grow"), std::string::npos) << err;
}

TEST(GrowthCli, AScenePatternIsGrownAgainWhenAGrowthMeshChanges) {
    TempDir tmp;
    sim::TriangleMesh ball = sim::make_uv_sphere(10, 16);
    sim::write_obj(tmp.file("ball.obj"), ball, {});
    for (sim::Vec3d &p : ball.positions) p = p * 0.5;
    sim::write_obj(tmp.file("small.obj"), ball, {});
    growing_preset(
        tmp, R"({"keys": [{"age": 0, "mesh": "small.obj"}, {"age": 2, "scale": 1}]})");
    const std::string scene =
        tmp.write("s.json", grow_scene("ball.obj", R"({"from": 0, "to": 2})"));
    std::string err;
    ASSERT_EQ(run_pelage("render " + scene, nullptr, &err), 0) << err;
    ASSERT_EQ(run_pelage("render " + scene, nullptr, &err), 0) << err;
    EXPECT_EQ(err.find("growing"), std::string::npos) << err;  // reused
    for (sim::Vec3d &p : ball.positions) p = p * 1.2;
    sim::write_obj(tmp.file("small.obj"), ball, {});
    ASSERT_EQ(run_pelage("render " + scene, nullptr, &err), 0) << err;
    EXPECT_NE(err.find("grown through other growth meshes"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
