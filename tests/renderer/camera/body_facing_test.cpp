// Which end is the head: synthetic animals (a body, a raised head on a neck, four legs
// and a thin raised tail) facing ±X and ±Z are framed from their head end, by shape for
// OFF files and by glTF 2.0 §3.4 ("the front of a glTF asset faces +Z", after the nodes'
// transforms) for glTF, through `pelage look`'s own plan (plan_look) as well as the
// camera functions. Before the head end was looked for, the camera turned towards the
// sign the principal axis happened to take, the same for an animal and its mirror
// image, so one of each ±X, ±Z pair was framed from behind.
#include "renderer/camera/body_facing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "renderer/camera/auto_frame.h"
#include "renderer/look/look.h"
#include "sim/mesh/mesh_load.h"
#include "tests/renderer/animation/gltf_builder.h"
#include "tests/test_paths.h"

namespace pelage::renderer {
namespace {

struct Animal {
    std::vector<Vec3f> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
};

// An ellipsoid (a UV sphere) about `c` with semi-axes `a`, `b`, `n` (mutually ⟂).
void add_ellipsoid(Animal *m, Vec3f c, Vec3f a, Vec3f b, Vec3f n) {
    constexpr int rings = 10, segments = 16;
    constexpr float pi = 3.14159265f;
    const uint32_t base = uint32_t(m->positions.size());
    m->positions.push_back(c + n);
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const float th = pi * float(i) / rings, ph = 2 * pi * float(j) / segments;
            m->positions.push_back(c + n * std::cos(th) +
                                   (a * std::cos(ph) + b * std::sin(ph)) * std::sin(th));
        }
    m->positions.push_back(c - n);
    const uint32_t south = uint32_t(m->positions.size() - 1);
    auto at = [&](int ring, int seg) {
        return base + 1 + uint32_t((ring - 1) * segments + (seg % segments));
    };
    for (int j = 0; j < segments; ++j) {
        m->triangles.push_back({base, at(1, j), at(1, j + 1)});
        m->triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
        for (int i = 1; i + 1 < rings; ++i) {
            m->triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m->triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
}

// A thin ellipsoid from `p` to `q`, of radius `r`.
void add_limb(Animal *m, Vec3f p, Vec3f q, float r) {
    const Vec3f axis = (q - p) * 0.5f;
    const Frame f = Frame::from_z(normalize(axis));
    add_ellipsoid(m, (p + q) * 0.5f, f.s * r, f.t * r, axis);
}

// An animal 1.8 long with its head towards `head` and `up` up, scaled by `scale` and
// moved by `offset`: the head and neck rise above the back; the tail, thin, rises too
// (as a bull's), and reaches further from the middle than the head.
Animal animal(Vec3f head, Vec3f up, float scale = 1, Vec3f offset = {0, 0, 0}) {
    const Vec3f side = cross(up, head);
    auto at = [&](float x, float y, float z) { return head * x + up * y + side * z; };
    Animal m;
    add_ellipsoid(&m, at(0, 0.55f, 0), head * 0.5f, side * 0.2f, up * 0.18f);
    add_limb(&m, at(0.4f, 0.6f, 0), at(0.6f, 0.85f, 0), 0.07f);  // neck
    add_ellipsoid(&m, at(0.66f, 0.88f, 0), head * 0.14f, side * 0.09f, up * 0.1f);
    add_limb(&m, at(-0.45f, 0.62f, 0), at(-0.95f, 0.8f, 0), 0.025f);  // tail
    for (float x : {-0.35f, 0.35f})
        for (float z : {-0.1f, 0.1f}) add_limb(&m, at(x, 0.45f, z), at(x, 0, z), 0.04f);
    for (Vec3f &p : m.positions) p = p * scale + offset;
    return m;
}

// Where the camera stands, seen from the middle of the animal.
Vec3f camera_offset(const Framing &f) { return f.camera.position - f.center; }

Framing frame_facing(const Animal &m, Vec3f up, Vec3f front, BodyFacing *facing) {
    *facing = body_facing(m.positions, m.triangles, up, front);
    FramingRequest rq;
    rq.up = up;
    rq.long_axis = facing->long_axis;
    rq.side_axis = facing->side_axis;
    return frame_points(m.positions, rq);
}

TEST(BodyFacing, TheShapeTurnsTheViewToTheHeadFacingAnyWay) {
    const Vec3f y{0, 1, 0}, z{0, 0, 1};
    struct Case {
        Vec3f head, up;
    };
    for (const Case c : {Case{{1, 0, 0}, y}, Case{{-1, 0, 0}, y}, Case{{0, 0, 1}, y},
                         Case{{0, 0, -1}, y}, Case{{1, 0, 0}, z}, Case{{-1, 0, 0}, z},
                         Case{{0, 1, 0}, z}, Case{{0, -1, 0}, z}})
        for (const float scale : {0.01f, 1.0f, 300.0f}) {
            const Animal m = animal(c.head, c.up, scale, Vec3f{3, -2, 5} * scale);
            BodyFacing facing;
            const Framing f = frame_facing(m, c.up, {0, 0, 0}, &facing);
            EXPECT_EQ(facing.rule, BodyFacing::Rule::shape);
            EXPECT_GT(dot(facing.long_axis, c.head), 0.99f)
                << "head " << c.head.x << "," << c.head.y << "," << c.head.z;
            // The camera turns 35° towards the head from the side, 15° up: its offset's
            // share along the head is sin 35° cos 15° = 0.55 of its distance.
            const Vec3f v = normalize(camera_offset(f));
            EXPECT_NEAR(dot(v, c.head), 0.554f, 0.01f);
            EXPECT_NEAR(std::abs(dot(v, facing.side_axis)), 0.791f, 0.01f);
            EXPECT_NEAR(dot(facing.side_axis, c.up), 0.0f, 1e-5f);
        }
}

TEST(BodyFacing, TheShapeIsNotFooledByALongRaisedTail) {
    // The tail reaches further from the middle than the head (0.95 against 0.8) and
    // rises above the back, but it is thin: the raised mass is the head, whichever sign
    // the axis comes with.
    const Animal m = animal({1, 0, 0}, {0, 1, 0});
    EXPECT_GT(towards_head(m.positions, m.triangles, {0, 1, 0}, {-1, 0, 0}).x, 0.99f);
    EXPECT_GT(towards_head(m.positions, m.triangles, {0, 1, 0}, {1, 0, 0}).x, 0.99f);
}

TEST(BodyFacing, GltfAndOnlyGltfHasAFront) {
    for (const char *p : {"a.gltf", "dir/B.GLB", "zoo.glb#giraffe", "x.glb"})
        EXPECT_GT(format_front(p).z, 0.99f) << p;
    for (const char *p : {"cow.off", "a.obj", "b.ply", "c.dae", "d.fbx", "zoo.gltf.off",
                          "procedural:icosphere:3", ""})
        EXPECT_EQ(length(format_front(p)), 0.0f) << p;
}

// A glTF of `m` in one mesh node with `rotation` (a quaternion x, y, z, w).
std::string animal_gltf(const Animal &m, const std::array<double, 4> &rotation) {
    test::GltfBuilder b;
    std::vector<float> pos;
    for (const Vec3f &p : m.positions) pos.insert(pos.end(), {p.x, p.y, p.z});
    std::vector<uint16_t> idx;
    for (const auto &t : m.triangles)
        for (uint32_t v : t) idx.push_back(uint16_t(v));
    const int position = b.add(pos, "VEC3", true);
    const int indices = b.add_u16(idx, "SCALAR", idx.size());
    b.doc["meshes"] = test::json::array(
        {{{"primitives", test::json::array({{{"attributes", {{"POSITION", position}}},
                                             {"indices", indices}}})}}});
    b.doc["nodes"] =
        test::json::array({{{"mesh", 0}, {"rotation", rotation}, {"name", "animal"}}});
    b.doc["scenes"] = test::json::array({{{"nodes", {0}}}});
    b.doc["scene"] = 0;
    return b.text();
}

BodyFacing loaded_facing(const std::string &path, Vec3f up) {
    const sim::TriangleMesh mesh = sim::load_mesh(path);
    Animal m;
    for (const sim::Vec3d &p : mesh.positions)
        m.positions.push_back({float(p.x), float(p.y), float(p.z)});
    for (const auto &t : mesh.triangles)
        m.triangles.push_back({uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2])});
    return body_facing(m.positions, m.triangles, up, format_front(path));
}

TEST(BodyFacing, AGltfFacesPlusZAfterItsNodesTransforms) {
    test::TempDir tmp;
    const Vec3f y{0, 1, 0};
    // Modelled facing +Z; modelled facing −Z and turned 180° about y by its node.
    for (const auto &[head_z, rotation] :
         {std::pair{1.0f, std::array<double, 4>{0, 0, 0, 1}},
          std::pair{-1.0f, std::array<double, 4>{0, 1, 0, 0}}}) {
        const std::string path =
            tmp.write(head_z > 0 ? "plus.gltf" : "minus.gltf",
                      animal_gltf(animal({0, 0, head_z}, y), rotation));
        const BodyFacing f = loaded_facing(path, y);
        EXPECT_EQ(f.rule, BodyFacing::Rule::front) << path;
        EXPECT_GT(f.long_axis.z, 0.99f) << path;
    }
    // The format's word wins over the shape: an animal whose raised mass is at −Z is
    // still framed from +Z, as a glTF viewer shows it.
    const BodyFacing against = loaded_facing(
        tmp.write("against.gltf", animal_gltf(animal({0, 0, -1}, y), {0, 0, 0, 1})), y);
    EXPECT_GT(against.long_axis.z, 0.99f);
    // Lying across Z, head at +X: the camera stands on the +Z side (not cross(up, long)
    // = −Z), turned to the head.
    const BodyFacing across = loaded_facing(
        tmp.write("across.gltf", animal_gltf(animal({1, 0, 0}, y), {0, 0, 0, 1})), y);
    EXPECT_EQ(across.rule, BodyFacing::Rule::shape);
    EXPECT_GT(across.long_axis.x, 0.99f);
    EXPECT_GT(across.side_axis.z, 0.99f);
    // Stood up on Z, a glTF's +Z front is vertical and says nothing: the shape decides.
    const BodyFacing upright =
        loaded_facing(tmp.write("upright.gltf",
                                animal_gltf(animal({0, -1, 0}, {0, 0, 1}), {0, 0, 0, 1})),
                      {0, 0, 1});
    EXPECT_EQ(upright.rule, BodyFacing::Rule::shape);
    EXPECT_LT(upright.long_axis.y, -0.99f);
}

std::string animal_off(const Animal &m) {
    std::ostringstream s;
    s << "OFF\n" << m.positions.size() << " " << m.triangles.size() << " 0\n";
    for (const Vec3f &p : m.positions) s << p.x << " " << p.y << " " << p.z << "\n";
    for (const auto &t : m.triangles)
        s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    return s.str();
}

// `pelage look`'s plan, as the command makes it: the scene's camera stands on the head's
// side of the animal's middle.
TEST(BodyFacing, LookFramesTheHeadEndOfOffAndGltfFiles) {
    test::TempDir tmp;
    const Vec3f y{0, 1, 0};
    struct Case {
        std::string file;
        Vec3f head;
        std::array<double, 4> rotation;
    };
    for (const Case &c : {Case{"px.off", {1, 0, 0}, {}}, Case{"mx.off", {-1, 0, 0}, {}},
                          Case{"pz.off", {0, 0, 1}, {}}, Case{"mz.off", {0, 0, -1}, {}},
                          Case{"pz.gltf", {0, 0, 1}, {0, 0, 0, 1}},
                          Case{"turned.gltf", {0, 0, -1}, {0, 1, 0, 0}}}) {
        const Animal m = animal(c.head, y);
        const bool gltf = c.file.find(".gltf") != std::string::npos;
        LookRequest rq;
        rq.mesh = tmp.write(c.file, gltf ? animal_gltf(m, c.rotation) : animal_off(m));
        rq.presets_dir = test::source_path("scenes/presets");
        rq.output = tmp.file("out.exr");
        const LookPlan plan = plan_look(rq, [](const std::string &) {});
        // The head in the file's space: the node's 180° turn about y flips it.
        const Vec3f head = gltf && c.rotation[1] == 1 ? -c.head : c.head;
        const Framing &f = plan.setup.framing;
        EXPECT_GT(dot(normalize(camera_offset(f)), head), 0.5f) << c.file;
    }
}

}  // namespace
}  // namespace pelage::renderer
