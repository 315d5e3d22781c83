// `pelage info FILE` lists a file's objects with the counts of each and of the whole
// file, checked against meshes whose counts are known by construction: an icosphere
// (20·4^k faces, 10·4^k + 2 vertices, closed), a fin of three triangles on one edge, and
// the tests' skinned glTF strip (a 9 × 2 grid of vertices, two joints, one morph target,
// clips of 2 s and 1 s). A file pelage cannot read is exit 2 naming it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "sim/mesh/mesh_load.h"
#include "tests/renderer/animation/skinned_strip.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// "ball", a subdivided icosphere (level 2), and "fin", three triangles around the edge
// from (5, 0, 0) to (5, 0, 1): one non-manifold edge, six boundary edges, and three
// pieces that meet only there.
std::string write_ball_and_fin(const TempDir &tmp) {
    const sim::TriangleMesh ball = sim::load_mesh("procedural:icosphere:2");
    std::ostringstream obj;
    obj.precision(17);
    for (const sim::Vec3d &p : ball.positions)
        obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    const size_t n = ball.num_vertices();
    obj << "v 5 0 0\nv 5 0 1\nv 6 0 0\nv 4 0 0\nv 5 1 0\n";
    obj << "o ball\n";
    for (const auto &t : ball.triangles)
        obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    obj << "o fin\n";
    for (int third = 3; third <= 5; ++third)
        obj << "f " << n + 1 << " " << n + 2 << " " << n + third << "\n";
    return tmp.write("ball_fin.obj", obj.str());
}

void expect_counts(const nlohmann::json &c, size_t triangles, size_t vertices,
                   size_t components, size_t boundary, size_t nonmanifold) {
    EXPECT_EQ(c["triangles"], triangles) << c.dump();
    EXPECT_EQ(c["vertices"], vertices) << c.dump();
    EXPECT_EQ(c["components"], components) << c.dump();
    EXPECT_EQ(c["boundary_edges"], boundary) << c.dump();
    EXPECT_EQ(c["nonmanifold_edges"], nonmanifold) << c.dump();
}

// The entry of `objects` named `name` (null when there is none).
nlohmann::json object_named(const nlohmann::json &objects, const std::string &name) {
    for (const nlohmann::json &o : objects)
        if (o["name"] == name) return o;
    return nullptr;
}

TEST(InfoCli, ListsEachObjectAndTheWholeFileWithTheirTopology) {
    TempDir tmp;
    const std::string file = write_ball_and_fin(tmp);
    std::string out, err;
    ASSERT_EQ(run_pelage("info --json " + file, &out, &err), 0) << err;
    EXPECT_EQ(err, "");  // listing a file is no reason to say its objects were merged
    const nlohmann::json j = nlohmann::json::parse(out);
    ASSERT_EQ(j["objects"].size(), 2u) << j.dump();
    EXPECT_EQ(j["objects"][0]["name"], "ball");
    EXPECT_EQ(j["objects"][0]["reference"], file + "#ball");
    expect_counts(j["objects"][0], 320, 162, 1, 0, 0);
    EXPECT_EQ(j["objects"][1]["name"], "fin");
    // Components join across manifold edges only, as the CRPS does.
    expect_counts(j["objects"][1], 3, 5, 3, 6, 1);
    expect_counts(j["total"], 323, 167, 4, 6, 1);
    EXPECT_FALSE(j["total"].contains("bones")) << "an OBJ carries no rig";
    EXPECT_TRUE(j["clips"].empty());

    // One object alone, and the same numbers in the text form.
    ASSERT_EQ(run_pelage("info --json " + file + "#fin", &out, &err), 0) << err;
    const nlohmann::json fin = nlohmann::json::parse(out);
    EXPECT_TRUE(fin["objects"].empty());
    expect_counts(fin["total"], 3, 5, 3, 6, 1);
    ASSERT_EQ(run_pelage("info " + file, &out, &err), 0) << err;
    EXPECT_NE(out.find("\n  fin "), std::string::npos) << out;
    EXPECT_NE(out.find("\n  ball "), std::string::npos) << out;
    EXPECT_NE(out.find(file + "#NAME"), std::string::npos) << out;
}

TEST(InfoCli, ListsASkinnedFilesBonesMorphTargetsAndClips) {
    TempDir tmp;
    const std::string file = tmp.write("strip.gltf", skinned_strip());
    std::string out, err;
    ASSERT_EQ(run_pelage("info --json " + file, &out, &err), 0) << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    // The strip: 16 triangles on 9 × 2 vertices, its rim 2 · 8 + 2 edges; skinned to
    // the two joints, with one morph target.
    const nlohmann::json strip = object_named(j["objects"], "strip");
    ASSERT_FALSE(strip.is_null()) << j.dump();
    expect_counts(strip, 16, 18, 1, 18, 0);
    EXPECT_EQ(strip["skinned"], true);
    EXPECT_EQ(strip["bones"], 2);
    EXPECT_EQ(strip["morph_targets"], 1);
    // The ear: one triangle placed by a node, no skin; "root" selects it too.
    for (const char *name : {"ear", "root"}) {
        const nlohmann::json ear = object_named(j["objects"], name);
        ASSERT_FALSE(ear.is_null()) << name << ": " << j.dump();
        expect_counts(ear, 1, 3, 1, 3, 0);
        EXPECT_EQ(ear["skinned"], false) << name;
        EXPECT_EQ(ear["morph_targets"], 0) << name;
    }
    // The ear's first corner, at the tip joint's (2, 0, 0) plus its node's (0.5, 0, 0),
    // is the strip's vertex there: welded into one in the whole file.
    expect_counts(j["total"], 17, 20, 2, 21, 0);
    EXPECT_EQ(j["total"]["bones"], 2);
    ASSERT_EQ(j["clips"].size(), 3u) << j.dump();
    EXPECT_EQ(j["clips"][0]["name"], "bend");
    EXPECT_NEAR(j["clips"][0]["seconds"].get<double>(), 2.0, 1e-6);
    EXPECT_EQ(j["clips"][1]["name"], "still");
    EXPECT_EQ(j["clips"][2]["name"], "roll");
    EXPECT_NEAR(j["clips"][2]["seconds"].get<double>(), 1.0, 1e-6);
    ASSERT_EQ(run_pelage("info " + file, &out, &err), 0) << err;
    EXPECT_NE(out.find("skinned, 2 bones; 1 morph target"), std::string::npos) << out;
    EXPECT_NE(out.find("\n    bend  2 s\n"), std::string::npos) << out;
}

TEST(InfoCli, AFileItCannotReadIsExitTwoNamingIt) {
    TempDir tmp;
    std::string out, err;
    const std::string missing = tmp.file("missing.glb");
    EXPECT_EQ(run_pelage("info " + missing, &out, &err), 2);
    EXPECT_NE(err.find(missing), std::string::npos) << err;
    const std::string broken = tmp.write("broken.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
    EXPECT_EQ(run_pelage("info " + broken, &out, &err), 2);
    EXPECT_NE(err.find(broken), std::string::npos) << err;
    const std::string file = write_ball_and_fin(tmp);
    EXPECT_EQ(run_pelage("info " + file + "#okapi", &out, &err), 2);
    EXPECT_NE(err.find("no object named \"okapi\" (the file's objects: \"ball\", "
                       "\"fin\")"),
              std::string::npos)
        << err;
    EXPECT_EQ(out, "");
}

}  // namespace
}  // namespace pelage::test
