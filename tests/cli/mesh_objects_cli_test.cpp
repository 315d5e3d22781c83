// One object of a multi-object mesh file, FILE#NAME, through every command that takes a
// mesh: `pelage sim`, `stats`, `crps` and a rendered scene whose clonal_mosaic plugin
// loads the mesh from the same reference; unknown names exit 2 listing the names there
// are, and loading the whole file says how many objects it merged.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// An OBJ holding "ball" (a 320-triangle icosphere) and "stand" (one triangle below it).
std::string write_two_objects(const TempDir &tmp) {
    const sim::TriangleMesh ball = sim::load_mesh("procedural:icosphere:2");
    std::ostringstream obj;
    obj.precision(17);
    for (const sim::Vec3d &p : ball.positions)
        obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    obj << "v -1 -2 -1\nv 1 -2 -1\nv 0 -2 1\n";
    obj << "o ball\n";
    for (const auto &t : ball.triangles)
        obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    const size_t n = ball.num_vertices();
    obj << "o stand\nf " << n + 1 << " " << n + 2 << " " << n + 3 << "\n";
    return tmp.write("two.obj", obj.str());
}

TEST(MeshObjectsCli, OneObjectOfAFileIsSimulatedMeasuredAndRendered) {
    TempDir tmp;
    const std::string file = write_two_objects(tmp);
    const std::string cells = simulate_two_type_cells(tmp, file + "#ball", 200);

    std::string out, err;
    ASSERT_EQ(run_pelage("crps --mesh " + file + "#ball", &out, &err), 0) << err;
    EXPECT_NE(out.find("triangles                 320"), std::string::npos) << out;
    EXPECT_EQ(err.find("merged"), std::string::npos) << err;
    ASSERT_EQ(run_pelage("stats " + cells + " --mesh " + file +
                             "#ball --area-samples 2000 --json",
                         &out, &err),
              0)
        << err;
    EXPECT_TRUE(nlohmann::json::parse(out).contains("area_fraction_by_type"));

    const std::string scene = tmp.write("s.json", R"({
      "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
      "film": {"width": 16, "height": 16, "spp": 1},
      "lights": [{"type": "environment"}],
      "objects": [{"mesh": "two.obj#ball", "cells": "mosaic.cells",
                   "material": {"shader": "clonal_mosaic"}},
                  {"mesh": "two.obj#stand"}]})");
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + tmp.file("o.exr"), &out, &err),
              0)
        << err;
}

TEST(MeshObjectsCli, UnknownNamesExit2ListingTheNamesAndMergingIsNoted) {
    TempDir tmp;
    const std::string file = write_two_objects(tmp);
    std::string out, err;
    EXPECT_EQ(run_pelage("crps --mesh " + file + "#okapi", &out, &err), 2);
    EXPECT_NE(err.find(file + ": no object named \"okapi\" (the file's objects: "
                              "\"ball\", \"stand\")"),
              std::string::npos)
        << err;
    const std::string scene = tmp.write("s.json", R"({"camera": {},
      "objects": [{"mesh": "two.obj#okapi"}]})");
    EXPECT_EQ(run_pelage("render " + scene + " -o " + tmp.file("o.exr"), &out, &err), 2);
    EXPECT_NE(err.find("no object named \"okapi\""), std::string::npos) << err;
    EXPECT_NE(err.find("objects[0].mesh"), std::string::npos) << err;

    ASSERT_EQ(run_pelage("crps --mesh " + file, &out, &err), 0) << err;
    EXPECT_NE(err.find(file +
                       ": merged its 2 objects into one mesh (names: ball, stand); "
                       "select one with " +
                       file + "#NAME"),
              std::string::npos)
        << err;
    EXPECT_NE(out.find("triangles                 321"), std::string::npos) << out;
}

}  // namespace
}  // namespace pelage::test
