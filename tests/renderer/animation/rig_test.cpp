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
#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "tests/renderer/animation/armature_tube.h"
#include "tests/renderer/animation/gltf_reference.h"
#include "tests/renderer/animation/skinned_strip.h"
#include "tests/test_paths.h"

namespace pelage::renderer {
namespace {

using json = nlohmann::json;
using test::GltfReference;
using test::skinned_strip;

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
    EXPECT_EQ(rig.clip_names(), (std::vector<std::string>{"bend", "still", "roll"}));
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

TEST(Rig, NormalsTurnWithTheSkin) {
    // The flat strip's normals are +z at rest; the roll turns the whole skin 90° about
    // x, so every normal, joint-blended or not, becomes R_x(90°)·z = (0, −1, 0).
    test::TempDir tmp;
    const std::string path = tmp.write("strip.gltf", skinned_strip());
    const Rig rig = Rig::read(path);
    sim::MeshLoadReport report;
    sim::TriangleMesh mesh = sim::load_mesh(path + "#strip", &report);
    unweld(report, &mesh);
    mesh.corner_normals.assign(3 * mesh.num_triangles(), sim::Vec3d{0, 0, 1});
    const Rig strip = Rig::read(path + "#strip");
    pose_mesh(strip, strip.clip("roll"), 1.0, &mesh);
    for (const sim::Vec3d &n : mesh.corner_normals) {
        EXPECT_NEAR(n.x, 0, 1e-6);
        EXPECT_NEAR(n.y, -1, 1e-6);
        EXPECT_NEAR(n.z, 0, 1e-6);
    }
    // Halfway, 45°.
    mesh.corner_normals.assign(3 * mesh.num_triangles(), sim::Vec3d{0, 0, 1});
    pose_mesh(strip, strip.clip("roll"), 0.5, &mesh);
    EXPECT_NEAR(mesh.corner_normals[0].y, -std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(mesh.corner_normals[0].z, std::sqrt(0.5), 1e-6);
    EXPECT_EQ(rig.clip_names().size(), 3u);
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

TEST(Rig, PosesAStillOfAnArmatureExportAsTheGltfSpecificationDoes) {
    // The tube's mesh node sits under a 0.01-scaled, turned armature; without clips the
    // rig still reads (Clips::optional), and the default pose puts the welded mesh
    // where the reference puts the file's triangles at rest: upright, 1.5 tall, not
    // through the mesh node's transform.
    test::TempDir tmp;
    json doc = json::parse(test::armature_tube(12, 6));
    doc.erase("animations");
    const std::string path = tmp.write("tube.gltf", doc.dump());
    EXPECT_THROW(Rig::read(path), InputError);  // a clip asked of a file without any
    const Rig rig = Rig::read(path, Rig::Clips::optional);
    EXPECT_TRUE(rig.skinned());
    EXPECT_TRUE(rig.clip_names().empty());
    sim::MeshLoadReport report;
    sim::TriangleMesh mesh = sim::load_mesh(path, &report);
    EXPECT_EQ(report.read.skinned_pieces, 1u);
    EXPECT_LT(mesh.bounds().diagonal(), 0.05);  // as read: 1/100 of the size
    const size_t vertices = mesh.num_vertices(), triangles = mesh.num_triangles();
    pose_default(rig, report, &mesh);
    EXPECT_EQ(mesh.num_vertices(), vertices);  // welded as loaded
    ASSERT_EQ(mesh.num_triangles(), triangles);
    const auto expected = GltfReference(path).triangles(-1, 0);
    double worst = 0;
    for (size_t t = 0; t < mesh.num_triangles(); ++t) {
        const auto &e = expected.at(mesh.source_face[t]);
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d p = mesh.vertex(sim::TriId(t), c);
            worst =
                std::max(worst, length(p - sim::Vec3d{e[size_t(c)][0], e[size_t(c)][1],
                                                      e[size_t(c)][2]}));
        }
    }
    EXPECT_LT(worst, 1e-5);  // the file's floats
    EXPECT_NEAR(mesh.bounds().hi.y - mesh.bounds().lo.y, test::armature_tube_height,
                1e-6);
}

TEST(Rig, FileNormalsUnderATransformedNodeTurnWithTheSkinOnce) {
    // The file's normals as read went through the armature's turn; a pose starts from
    // the file's own, so at the clip's start (the default pose) they point out of the
    // tube again, not turned a second time.
    test::TempDir tmp;
    const std::string path = tmp.write("tube.gltf", test::armature_tube(12, 6));
    const Rig rig = Rig::read(path);
    sim::MeshLoadReport report;
    sim::TriangleMesh mesh = sim::load_mesh(path, &report);
    ASSERT_FALSE(mesh.corner_normals.empty());
    unweld(report, &mesh);
    pose_mesh(rig, rig.clip("Sway"), 0, &mesh);
    double worst = 1;
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d p = mesh.vertex(sim::TriId(t), c);
            const sim::Vec3d n = mesh.corner_normals[3 * t + size_t(c)];
            worst = std::min(worst, (n.x * p.x + n.z * p.z) / std::hypot(p.x, p.z));
        }
    EXPECT_GT(worst, 0.9999);
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
