// The rig (renderer/animation) against the glTF reference written from the
// specification (gltf_reference.h): a skinned, morphing strip with a rigid part made
// here, and the Khronos sample fox (Fox.glb) when $PELAGE_TEST_ASSETS names a folder
// holding it (the repository ships no third-party models).
#include "renderer/animation/rig.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "tests/renderer/animation/gltf_reference.h"
#include "tests/test_paths.h"

namespace pelage::renderer {
namespace {

using json = nlohmann::json;
using test::GltfReference;

std::string base64(const std::string &bytes) {
    static const char *abc =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 |
                           uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += abc[(v >> s) & 63];
    }
    if (i < bytes.size()) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += abc[(v >> 18) & 63];
        out += abc[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// Builds a glTF document's one buffer: each add() is one bufferView and one accessor.
struct GltfBuilder {
    json doc = {{"asset", {{"version", "2.0"}}}};
    std::string bin;
    int add(const std::vector<float> &v, const char *type, bool minmax = false) {
        return add_raw(
            std::string(reinterpret_cast<const char *>(v.data()), 4 * v.size()), 5126,
            type,
            v.size() / (std::strcmp(type, "SCALAR") == 0 ? 1
                        : std::strcmp(type, "VEC3") == 0 ? 3
                        : std::strcmp(type, "VEC4") == 0 ? 4
                        : std::strcmp(type, "MAT4") == 0 ? 16
                                                         : 2),
            minmax ? &v : nullptr);
    }
    int add_u16(const std::vector<uint16_t> &v, const char *type, size_t count) {
        return add_raw(
            std::string(reinterpret_cast<const char *>(v.data()), 2 * v.size()), 5123,
            type, count, nullptr);
    }
    int add_raw(const std::string &bytes, int component, const char *type, size_t count,
                const std::vector<float> *positions) {
        while (bin.size() % 4) bin.push_back('\0');
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
        bin += bytes;
        json a = {{"bufferView", doc["bufferViews"].size() - 1},
                  {"componentType", component},
                  {"count", count},
                  {"type", type}};
        if (positions) {
            std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
            for (size_t i = 0; i < positions->size(); ++i)
                lo[i % 3] = std::min(lo[i % 3], (*positions)[i]),
                       hi[i % 3] = std::max(hi[i % 3], (*positions)[i]);
            a["min"] = lo;
            a["max"] = hi;
        }
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size() - 1);
    }
    std::string text() {
        doc["buffers"] = json::array(
            {{{"byteLength", bin.size()},
              {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        return doc.dump();
    }
};

// A strip 4 long along x, skinned to a root joint and a tip joint at x = 2 (weights
// blending over 1 ≤ x ≤ 3), with a morph target lifting its end, and a rigid triangle
// (an "ear") on the tip joint. Clip "bend": the tip turns 160° about z and back, the
// root slides, the morph weight goes 0 → 1. Clip "still": one key, the rest.
// `weight_scale` multiplies every vertex's weights (1: valid).
std::string skinned_strip(double weight_scale = 1) {
    GltfBuilder b;
    std::vector<float> pos, joints_w, morph;
    std::vector<uint16_t> idx;
    std::vector<uint8_t> joints;
    const int columns = 9;
    for (int c = 0; c < columns; ++c)
        for (int r = 0; r < 2; ++r) {
            const float x = 4.0f * float(c) / float(columns - 1), y = 0.5f * float(r);
            pos.insert(pos.end(), {x, y, 0});
            const float w = std::clamp((x - 1) / 2, 0.0f, 1.0f);
            joints.insert(joints.end(), {0, 1, 0, 0});
            joints_w.insert(joints_w.end(), {float(weight_scale) * (1 - w),
                                             float(weight_scale) * w, 0, 0});
            morph.insert(morph.end(), {0, 0, x >= 3 ? 0.5f : 0.0f});
        }
    for (int c = 0; c + 1 < columns; ++c) {
        const uint16_t a = uint16_t(2 * c), d = uint16_t(a + 1), e = uint16_t(a + 2),
                       f = uint16_t(a + 3);
        idx.insert(idx.end(), {a, e, d, d, e, f});
    }
    const int p = b.add(pos, "VEC3", true);
    const int m = b.add(morph, "VEC3", true);
    const int jw = b.add(joints_w, "VEC4");
    const int j = b.add_raw(std::string(joints.begin(), joints.end()), 5121, "VEC4",
                            joints.size() / 4, nullptr);
    const int i = b.add_u16(idx, "SCALAR", idx.size());
    const std::vector<float> ear_pos = {0, 0, 0, 0.4f, 0, 0, 0, 0.3f, 0.2f};
    const int ep = b.add(ear_pos, "VEC3", true);
    const int ei = b.add_u16({0, 1, 2}, "SCALAR", 3);
    // Inverse bind matrices (column-major): the root at the origin, the tip at x = 2.
    const int ibm = b.add({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,  //
                           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -2, 0, 0, 1},
                          "MAT4");
    const int times = b.add({0, 1, 2}, "SCALAR");
    const float s80 = std::sin(80 * 3.14159265f / 180),
                c80 = std::cos(80 * 3.14159265f / 180);
    const float s20 = std::sin(20 * 3.14159265f / 180),
                c20 = std::cos(20 * 3.14159265f / 180);
    const int tip_rot = b.add({0, 0, 0, 1, 0, 0, s80, c80, 0, 0, s20, c20}, "VEC4");
    const int root_pos = b.add({0, 0, 0, 0.5f, 0.25f, 0, 1, 0.5f, 0}, "VEC3");
    const int morph_w = b.add({0, 0.3f, 1}, "SCALAR");
    const int one_time = b.add({0}, "SCALAR");
    const int one_pos = b.add({0, 0, 0}, "VEC3");
    b.doc["meshes"] = json::array(
        {{{"name", "strip"},
          {"weights", {0.0}},
          {"primitives",
           {{{"attributes", {{"POSITION", p}, {"JOINTS_0", j}, {"WEIGHTS_0", jw}}},
             {"indices", i},
             {"targets", {{{"POSITION", m}}}}}}}},
         {{"name", "ear"},
          {"primitives", {{{"attributes", {{"POSITION", ep}}}, {"indices", ei}}}}}});
    b.doc["nodes"] =
        json::array({{{"name", "strip"}, {"mesh", 0}, {"skin", 0}},
                     {{"name", "root"}, {"children", {2}}},
                     {{"name", "tip"}, {"translation", {2, 0, 0}}, {"children", {3}}},
                     {{"name", "ear"}, {"mesh", 1}, {"translation", {0.5, 0, 0}}}});
    b.doc["skins"] = json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", ibm}}});
    b.doc["scenes"] = json::array({{{"nodes", {0, 1}}}});
    b.doc["scene"] = 0;
    b.doc["animations"] = json::array(
        {{{"name", "bend"},
          {"samplers",
           {{{"input", times}, {"output", tip_rot}},
            {{"input", times}, {"output", root_pos}},
            {{"input", times}, {"output", morph_w}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
            {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}},
            {{"sampler", 2}, {"target", {{"node", 0}, {"path", "weights"}}}}}}},
         {{"name", "still"},
          {"samplers", {{{"input", one_time}, {"output", one_pos}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}}}});
    return b.text();
}

// The largest distance of a posed triangle's corner from the reference's, over the
// mesh, relative to the rest mesh's bounding-box diagonal.
double worst_error(const std::string &path, const Rig &rig, int clip, double seconds,
                   const GltfReference &ref, int ref_clip) {
    sim::MeshLoadReport report;
    sim::TriangleMesh mesh = sim::load_mesh(path, &report);
    const double diagonal = mesh.bounds().diagonal();
    unweld(report, &mesh);
    pose_mesh(rig, clip, seconds, &mesh);
    const auto expected = ref.triangles(ref_clip, seconds);
    double worst = 0;
    for (size_t t = 0; t < mesh.num_triangles(); ++t) {
        const auto &e = expected.at(mesh.source_face[t]);
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d p = mesh.vertex(sim::TriId(t), c);
            const sim::Vec3d q{e[size_t(c)][0], e[size_t(c)][1], e[size_t(c)][2]};
            worst = std::max(worst, length(p - q) / diagonal);
        }
    }
    return worst;
}

TEST(Rig, PosesASkinnedMorphingStripAsTheGltfSpecificationDoes) {
    test::TempDir tmp;
    const std::string path = tmp.write("strip.gltf", skinned_strip());
    const Rig rig = Rig::read(path);
    const GltfReference ref(path);
    EXPECT_TRUE(rig.skinned());
    EXPECT_EQ(rig.clip_names(), (std::vector<std::string>{"bend", "still"}));
    EXPECT_DOUBLE_EQ(rig.duration_seconds(rig.clip("bend")), 2.0);
    const int bend = rig.clip("bend");
    EXPECT_TRUE(rig.moves_mesh(bend));
    // Between keys (where spherical and plain linear interpolation of the rotation
    // differ), on keys, and beyond the last key.
    for (double t : {0.0, 0.25, 0.7, 1.0, 1.6, 2.0, 3.0})
        EXPECT_LT(worst_error(path, rig, bend, t, ref, ref.animation("bend")), 1e-5)
            << "t = " << t;
    // The strip does move: the tip end is far from its rest place at t = 1.
    EXPECT_GT(worst_error(path, rig, bend, 1.0, ref, -1), 0.3);
    // A clip that moves nothing leaves the rest pose (the nodes as the file places them).
    EXPECT_LT(worst_error(path, rig, rig.clip("still"), 0.0, ref, -1), 1e-6);
}

TEST(Rig, PosesTheKhronosFoxAsTheGltfSpecificationDoes) {
    const char *assets = std::getenv("PELAGE_TEST_ASSETS");
    const std::string fox = std::string(assets ? assets : "") + "/Fox.glb";
    if (!assets || !std::filesystem::exists(fox))
        GTEST_SKIP() << "set PELAGE_TEST_ASSETS to a folder holding Fox.glb";
    const Rig rig = Rig::read(fox);
    const GltfReference ref(fox);
    ASSERT_EQ(rig.clip_names().size(), 1u);
    const int clip = 0;
    const int ref_clip = ref.animation(rig.clip_names()[0]);
    ASSERT_GE(ref_clip, 0);
    EXPECT_TRUE(rig.skinned());
    EXPECT_TRUE(rig.moves_mesh(clip));
    const double d = rig.duration_seconds(clip);
    for (double f : {0.0, 0.13, 0.37, 0.5, 0.81, 0.99})
        EXPECT_LT(worst_error(fox, rig, clip, f * d, ref, ref_clip), 1e-5)
            << "t = " << f * d;
}

TEST(Rig, NamesTheFileAndItsClipsInErrors) {
    test::TempDir tmp;
    const std::string path = tmp.write("strip.gltf", skinned_strip());
    const Rig rig = Rig::read(path);
    try {
        rig.clip("walk", "objects[0].animation.clip");
        FAIL() << "no error";
    } catch (const InputError &e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.field(), "objects[0].animation.clip");
        EXPECT_NE(std::string(e.what()).find("\"bend\", \"still\""), std::string::npos)
            << e.what();
    }
    // A format without animation, and weights that do not sum to 1.
    const std::string obj = tmp.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_THROW(Rig::read(obj), InputError);
    const std::string bad = tmp.write("bad.gltf", skinned_strip(0.6));
    try {
        Rig::read(bad);
        FAIL() << "no error";
    } catch (const InputError &e) {
        EXPECT_EQ(e.file(), bad);
        EXPECT_NE(std::string(e.what()).find("sum to 0.6"), std::string::npos)
            << e.what();
    }
    // A file without clips.
    json doc = json::parse(skinned_strip());
    doc.erase("animations");
    const std::string still = tmp.write("still.gltf", doc.dump());
    try {
        Rig::read(still);
        FAIL() << "no error";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("no animation clips"), std::string::npos)
            << e.what();
    }
}

// The error a scene gives, "" when it parses.
std::string scene_error(const std::string &text, const std::string &path) {
    try {
        parse_scene(text, path);
    } catch (const InputError &e) {
        return e.what();
    }
    return "";
}

TEST(SceneClip, PlaysTheNamedClipAtTheFramesTime) {
    test::TempDir tmp;
    tmp.write("strip.gltf", skinned_strip());
    const std::string path = tmp.file("scene.json");
    auto scene = [](const std::string &object_animation) {
        return R"({"camera": {}, "animation": {"frames": 48, "fps": 24},
                   "objects": [{"mesh": "strip.gltf", "animation": )" +
               object_animation + "}]}";
    };
    const SceneDesc d = parse_scene(scene(R"({"clip": "bend", "start": 0.5})"), path);
    ASSERT_TRUE(d.objects[0].clip);
    EXPECT_DOUBLE_EQ(d.objects[0].clip_seconds, 0.5);  // a still shows the start
    EXPECT_DOUBLE_EQ(scene_at_frame(d, 12).objects[0].clip_seconds, 1.0);
    EXPECT_DOUBLE_EQ(scene_at_frame(d, 42).objects[0].clip_seconds, 0.25);  // looped
    const SceneDesc held =
        parse_scene(scene(R"({"clip": "bend", "loop": false, "fps": 12})"), path);
    EXPECT_DOUBLE_EQ(scene_at_frame(held, 6).objects[0].clip_seconds, 0.5);
    EXPECT_DOUBLE_EQ(scene_at_frame(held, 40).objects[0].clip_seconds, 2.0);

    const std::string unknown = scene_error(scene(R"({"clip": "walk"})"), path);
    EXPECT_NE(unknown.find("objects[0].animation.clip"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("\"bend\", \"still\""), std::string::npos) << unknown;
    EXPECT_NE(scene_error(scene(R"({"clip": "bend", "fps": 0})"), path), "");
    EXPECT_NE(scene_error(scene(R"({"clip": "bend", "speed": 2})"), path), "");
    const std::string procedural = scene_error(
        R"({"camera": {}, "objects": [{"mesh": "procedural:sphere:8x8",
            "animation": {"clip": "bend"}}]})",
        path);
    EXPECT_NE(procedural.find("procedural mesh has no clips"), std::string::npos)
        << procedural;
}

TEST(Rig, ClipTimeLoopsOrHolds) {
    EXPECT_DOUBLE_EQ(clip_time(2.5, 2.0, true), 0.5);
    EXPECT_DOUBLE_EQ(clip_time(-0.5, 2.0, true), 1.5);
    EXPECT_DOUBLE_EQ(clip_time(2.5, 2.0, false), 2.0);
    EXPECT_DOUBLE_EQ(clip_time(-1, 2.0, false), 0.0);
}

}  // namespace
}  // namespace pelage::renderer
