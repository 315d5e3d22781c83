// Scene files: defaults, relative paths, and errors that name the JSON path.
#include "renderer/scene_file.h"

#include <gtest/gtest.h>

#include "sim/input_error.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

std::string field_of(const std::string &json) {
    try {
        parse_scene(json, "/scenes/s.json");
    } catch (const InputError &e) {
        return e.field();
    }
    return "(no error)";
}

TEST(SceneFile, DefaultsAndPathsRelativeToTheSceneFile) {
    const SceneDesc s = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "meshes/cow.off", "cells": "../c/cow.cells"}],
                                        "film": {"output": "out/x.exr"}})",
        "/data/scenes/s.json");
    EXPECT_EQ(s.objects[0].mesh, "/data/scenes/meshes/cow.off");
    EXPECT_EQ(s.objects[0].cells, "/data/c/cow.cells");
    EXPECT_EQ(s.film.output, "/data/scenes/out/x.exr");
    EXPECT_EQ(s.objects[0].material.shader, "diffuse");
    EXPECT_EQ(s.film.spp, 16);
    EXPECT_EQ(s.integrator.max_depth, 8);
}

TEST(SceneFile, ProceduralMeshesAreNotPaths) {
    const SceneDesc s = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "procedural:sphere:8x8"}]})", "/a/s.json");
    EXPECT_EQ(s.objects[0].mesh, "procedural:sphere:8x8");
}

TEST(SceneFile, ErrorsNameTheJsonPath) {
    EXPECT_EQ(field_of(R"({"camera": {"fovv": 3}, "objects": []})"), "camera.fovv");
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "objects": [{"mesh": "a.off"}, {"mesh": "b.off", "material": {"bsdf": "glass"}}]})"),
        "objects[1].material.bsdf");
    EXPECT_EQ(field_of(R"({"camera": {}, "film": {"width": 0}, "objects": []})"),
              "film.width");
    EXPECT_EQ(field_of(R"({"camera": {}, "film": {"width": 1.5}, "objects": []})"),
              "film.width");
    EXPECT_EQ(field_of(R"({"camera": {"position": [1, 2]}, "objects": []})"),
              "camera.position");
    EXPECT_EQ(field_of(R"({"camera": {"position": [1, "x", 2]}, "objects": []})"),
              "camera.position[1]");
    EXPECT_EQ(field_of(R"({"camera": {}, "lights": [{"type": "point"}], "objects": []})"),
              "lights[0].type");
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "lights": [{"type": "quad", "corner": [0,0,0], "edge_u": [1,0,0], "edge_v": [2,0,0]}], "objects": []})"),
        "lights[0].edge_v");
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "objects": [{"mesh": "a.off", "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0], "scale": 2}}]})"),
        "objects[0].transform.scale");
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "objects": [{"mesh": "a.off", "material": {"roughness": 0.2}}]})"),
        "objects[0].material.roughness");
    EXPECT_EQ(field_of(R"({"camera": {}})"), "objects");
    EXPECT_EQ(field_of(R"({"camera": {}, "objects": [], "extra": 1})"), "extra");
    EXPECT_EQ(
        field_of(
            R"({"camera": {"position": [0,0,0], "look_at": [0,0,0]}, "objects": []})"),
        "camera.look_at");
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "objects": [{"mesh": "a.off", "transform": {"scale": [1, 0, 1]}}]})"),
        "objects[0].transform");
}

TEST(SceneFile, InvalidJsonNamesTheLine) {
    try {
        parse_scene("{\n  \"camera\": {},\n  \"objects\": [,]\n}", "/s.json");
        FAIL();
    } catch (const InputError &e) {
        EXPECT_EQ(e.line(), 3u);
    }
}

}  // namespace
}  // namespace pelage::test
