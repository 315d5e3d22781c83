// Scene files: defaults, relative paths, and errors that name the JSON path.
#include "renderer/scene_file/scene_file.h"

#include <gtest/gtest.h>

#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/input_error.h"
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

// "colour" or "color": the same light either way, errors named as the file spells the
// key, and both spellings in one object refused naming it.
TEST(SceneFile, ColourReadsInEitherSpelling) {
    const auto light = [](const std::string &fields) {
        return R"({"camera": {}, "lights": [{"type": "environment", )" + fields +
               R"(}], "objects": []})";
    };
    const SceneDesc a = parse_scene(light(R"("colour": [0.1, 0.2, 0.3])"), "/s.json");
    const SceneDesc b = parse_scene(light(R"("color": [0.1, 0.2, 0.3])"), "/s.json");
    EXPECT_EQ(a.lights[0].color.x, 0.1f);
    EXPECT_EQ(b.lights[0].color.x, a.lights[0].color.x);
    EXPECT_EQ(b.lights[0].color.y, a.lights[0].color.y);
    EXPECT_EQ(b.lights[0].color.z, a.lights[0].color.z);
    EXPECT_EQ(field_of(light(R"("color": -1)")), "lights[0].color");
    EXPECT_EQ(field_of(light(R"("colour": -1)")), "lights[0].colour");
    EXPECT_EQ(field_of(light(R"("colour": 1, "color": 1)")), "lights[0].colour");
    EXPECT_EQ(field_of(light(R"("color": 1, "image": "sky.exr")")), "lights[0].color");
    EXPECT_EQ(field_of(light(R"("colr": 1)")), "lights[0].colr");
}

TEST(SceneFile, MeshObjectsKeepTheirNameAsWritten) {
    const SceneDesc s = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "m/zoo.glb#herd/../giraffe",
                                       "deform": ["m/../pose.fbx#giraffe"]}]})",
        "/a/s.json");
    EXPECT_EQ(s.objects[0].mesh, "/a/m/zoo.glb#herd/../giraffe");
    EXPECT_EQ(s.objects[0].deform[0], "/a/pose.fbx#giraffe");
    EXPECT_EQ(field_of(R"({"camera": {}, "objects": [{"mesh": "zoo.glb#"}]})"),
              "objects[0].mesh");
    EXPECT_EQ(field_of(R"({"camera": {}, "objects": [{"mesh": "a.obj",
                                                       "deform": ["b.obj", "c.obj#"]}]})"),
              "objects[0].deform[1]");
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

TEST(SceneFile, TurntableOrbitsTheCameraOrTurnsTheObjects) {
    const std::string base =
        R"({"camera": {"position": [0, 1, 4], "look_at": [0, 1, 0]},
            "objects": [{"mesh": "procedural:icosphere:1", "transform": {"translate": [1, 0, 0]}}],
            "animation": {"frames": 8, "turntable": {"axis": [0, 2, 0], "center": [0, 1, 0],
                          "degrees": 360, "target": ")";
    const SceneDesc cam = parse_scene(base + R"(camera"}}})", "/s.json");
    ASSERT_TRUE(cam.animation.turntable);
    EXPECT_FLOAT_EQ(cam.animation.turntable->axis.y, 1.0f);  // normalized
    // Frame 0 is the scene's own camera; frame 2 of 8 is a quarter turn about +y through
    // the centre: +z goes to +x, the distance to the centre and the height stay.
    const CameraDesc c0 = scene_at_frame(cam, 0).camera,
                     c2 = scene_at_frame(cam, 2).camera;
    EXPECT_NEAR(c0.position.z, 4, 1e-6);
    EXPECT_NEAR(c2.position.x, 4, 1e-5);
    EXPECT_NEAR(c2.position.y, 1, 1e-5);
    EXPECT_NEAR(c2.position.z, 0, 1e-5);
    EXPECT_NEAR(c2.look_at.x, 0, 1e-6);
    EXPECT_TRUE(scene_at_frame(cam, 2).objects[0].transform.m[0][3] == 1.0f);
    // The object target turns the objects' transforms instead, the camera stays.
    const SceneDesc obj = parse_scene(base + R"(object"}}})", "/s.json");
    const SceneDesc o2 = scene_at_frame(obj, 2);
    EXPECT_NEAR(o2.camera.position.z, 4, 1e-6);
    const Vec3f p = o2.objects[0].transform.point({0, 0, 0});  // was (1, 0, 0)
    EXPECT_NEAR(p.x, 0, 1e-5);
    EXPECT_NEAR(p.y, 0, 1e-5);
    EXPECT_NEAR(p.z, -1, 1e-5);
    // Bad fields name their JSON path.
    EXPECT_EQ(field_of(base + R"(camera", "degrees": "a lot"}}})"),
              "animation.turntable.degrees");
    EXPECT_EQ(field_of(base + R"(object", "objects": ["cow"]}}})"),
              "animation.turntable.objects[0]");
    EXPECT_EQ(field_of(base + R"(camera", "objects": ["object0"]}}})"),
              "animation.turntable.objects");
    // Only the named objects turn.
    const SceneDesc named = parse_scene(
        R"({"camera": {}, "objects": [{"name": "cow", "mesh": "procedural:icosphere:1"},
            {"name": "ground", "mesh": "procedural:plane:1x1", "transform": {"translate": [1, 0, 0]}}],
            "animation": {"frames": 4, "turntable": {"target": "object", "objects": ["cow"]}}})",
        "/s.json");
    EXPECT_TRUE(scene_at_frame(named, 1).objects[1].transform.m[0][3] == 1.0f);
    EXPECT_FALSE(scene_at_frame(named, 1).objects[0].transform.is_identity());
    EXPECT_EQ(
        field_of(
            R"({"camera": {}, "objects": [], "lights": [{"type": "environment"}], "animation": {"fps": -1}})"),
        "animation.fps");
}

TEST(SceneFile, DeformOnePoseBlendsFromRestToThePose) {
    const SceneDesc s = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "rest.obj", "deform": "pose.obj"}],
            "animation": {"frames": 5}})",
        "/d/s.json");
    EXPECT_EQ(s.objects[0].deform_mesh, "/d/pose.obj");
    EXPECT_EQ(s.objects[0].deform_weight, 1.0f);  // a still shows the pose
    EXPECT_EQ(scene_at_frame(s, 0).objects[0].deform_weight, 0.0f);
    EXPECT_EQ(scene_at_frame(s, 2).objects[0].deform_weight, 0.5f);
    EXPECT_EQ(scene_at_frame(s, 4).objects[0].deform_weight, 1.0f);
    const SceneDesc l = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "rest.obj", "deform": ["a.obj", "b.obj"]}],
            "animation": {"frames": 2}})",
        "/d/s.json");
    EXPECT_EQ(scene_at_frame(l, 1).objects[0].deform_mesh, "/d/b.obj");
    EXPECT_EQ(
        field_of(R"({"camera": {}, "objects": [{"mesh": "r.obj", "deform": [3]}]})"),
        "objects[0].deform[0]");
}

}  // namespace
}  // namespace pelage::test
