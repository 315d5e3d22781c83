// Mesh formats beyond OFF and OBJ (PLY; through assimp glTF, Collada, FBX), objects
// selected by name (assimp nodes and meshes, OBJ `o`/`g`), and OBJ materials. The files
// are written here byte by byte, so each reader is checked against positions known by
// construction, not against itself; Collada and FBX come from assimp's exporter fed a
// known mesh.
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <cmath>
#include <cstring>
#include <fstream>

#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

using test::TempDir;

std::string base64(const std::string &bytes) {
    static const char *table =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

template <typename T>
void append(std::string *bytes, std::initializer_list<T> values) {
    for (T v : values) bytes->append(reinterpret_cast<const char *>(&v), sizeof v);
}

// One triangle (0,0,0) (1,0,0) (0,1,0) with normal +z and UVs (0,0) (1,0) (0,1), placed
// three times by the node graph:
//   zoo (translate 10,0,0)
//   ├── giraffe (scale 2)              → (10,0,0) (12,0,0) (10,2,0)
//   ├── zebra (rotate 90° about z, translate 0,5,0) → (10,5,0) (10,6,0) (9,5,0)
//   └── mirror (scale -1,1,1)          → (10,0,0) (9,0,0) (10,1,0), winding kept
// The mesh is named "tri" and has a material "skin" with baseColorFactor (0.5, 0.25,
// 0.125) and the texture skin.png.
std::string gltf_buffer() {
    std::string b;
    append<float>(&b, {0, 0, 0, 1, 0, 0, 0, 1, 0});  // positions, offset 0
    append<float>(&b, {0, 0, 1, 0, 0, 1, 0, 0, 1});  // normals, offset 36
    append<float>(&b, {0, 0, 1, 0, 0, 1});           // uvs, offset 72
    append<uint16_t>(&b, {0, 1, 2, 0});              // indices, offset 96 (+ padding)
    return b;
}

std::string gltf_json(const std::string &buffer_uri, size_t buffer_bytes) {
    const double s = std::sqrt(0.5);
    return R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [
    {"name": "zoo", "translation": [10, 0, 0], "children": [1, 2, 3]},
    {"name": "giraffe", "mesh": 0, "scale": [2, 2, 2]},
    {"name": "zebra", "mesh": 0, "rotation": [0, 0, )" +
           std::to_string(s) + ", " + std::to_string(s) + R"(], "translation": [0, 5, 0]},
    {"name": "mirror", "mesh": 0, "scale": [-1, 1, 1]}
  ],
  "meshes": [{"name": "tri", "primitives": [{
    "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
    "indices": 3, "material": 0}]}],
  "materials": [{"name": "skin", "pbrMetallicRoughness": {
    "baseColorFactor": [0.5, 0.25, 0.125, 1], "baseColorTexture": {"index": 0}}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "skin.png"}],
  "buffers": [{)" +
           (buffer_uri.empty() ? std::string() : "\"uri\": \"" + buffer_uri + "\", ") +
           "\"byteLength\": " + std::to_string(buffer_bytes) + R"(}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 24},
    {"buffer": 0, "byteOffset": 96, "byteLength": 6}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ]
})";
}

std::string write_gltf(const TempDir &tmp) {
    const std::string b = gltf_buffer();
    return tmp.write(
        "zoo.gltf",
        gltf_json("data:application/octet-stream;base64," + base64(b), b.size()));
}

// The same scene as a binary .glb: header, JSON chunk, BIN chunk (glTF 2.0 §4.4).
std::string glb_bytes() {
    std::string json = gltf_json("", gltf_buffer().size());
    while (json.size() % 4) json += ' ';
    std::string bin = gltf_buffer();
    while (bin.size() % 4) bin += '\0';
    std::string out = "glTF";
    append<uint32_t>(&out, {2, uint32_t(12 + 8 + json.size() + 8 + bin.size())});
    append<uint32_t>(&out, {uint32_t(json.size()), 0x4E4F534Au});  // "JSON"
    out += json;
    append<uint32_t>(&out, {uint32_t(bin.size()), 0x004E4942u});  // "BIN\0"
    out += bin;
    return out;
}

void expect_near(Vec3d a, Vec3d b) {
    EXPECT_NEAR(a.x, b.x, 1e-6);
    EXPECT_NEAR(a.y, b.y, 1e-6);
    EXPECT_NEAR(a.z, b.z, 1e-6);
}

// The triangle's corners as read, in triangle order.
void expect_triangle(const TriangleMesh &m, TriId t, Vec3d a, Vec3d b, Vec3d c) {
    SCOPED_TRACE("triangle " + std::to_string(t));
    expect_near(m.vertex(t, 0), a);
    expect_near(m.vertex(t, 1), b);
    expect_near(m.vertex(t, 2), c);
}

std::string error_of(const std::string &spec) {
    try {
        (void)load_mesh(spec);
    } catch (const InputError &e) {
        return e.what();
    }
    return "";
}

void check_zoo(const TriangleMesh &m, const std::string &dir) {
    ASSERT_EQ(m.num_triangles(), 3u);
    expect_triangle(m, 0, {10, 0, 0}, {12, 0, 0}, {10, 2, 0});
    expect_triangle(m, 1, {10, 5, 0}, {10, 6, 0}, {9, 5, 0});
    // Mirrored: corners 1 and 2 swap so the winding still faces the normal.
    expect_triangle(m, 2, {10, 0, 0}, {10, 1, 0}, {9, 0, 0});
    ASSERT_EQ(m.corner_normals.size(), 9u);
    for (TriId t = 0; t < 3; ++t) {
        const Vec3d n = m.face_normal_unnormalized(t);
        EXPECT_GT(n.z, 0) << "triangle " << t;
        for (int c = 0; c < 3; ++c) expect_near(m.corner_normals[3 * t + c], {0, 0, 1});
    }
    // glTF's v runs down the image; assimp flips it to OBJ's convention (v up).
    ASSERT_EQ(m.corner_uvs.size(), 9u);
    EXPECT_EQ(m.corner_uvs[0], (Vec2d{0, 1}));
    EXPECT_EQ(m.corner_uvs[1], (Vec2d{1, 1}));
    EXPECT_EQ(m.corner_uvs[2], (Vec2d{0, 0}));
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].name, "skin");
    expect_near(m.materials[0].diffuse, {0.5, 0.25, 0.125});
    EXPECT_EQ(m.materials[0].diffuse_texture, dir + "/skin.png");
    EXPECT_EQ(m.triangle_material, (std::vector<uint32_t>{0, 0, 0}));
}

TEST(MeshFormats, GltfNodeTransformsAreBakedIntoPositionsAndNormals) {
    TempDir tmp;
    MeshReadStats st;
    const TriangleMesh m = read_mesh(write_gltf(tmp), &st);
    check_zoo(m, tmp.path().string());
    EXPECT_EQ(st.pieces_read, 3u);
    EXPECT_EQ(st.object_names,
              (std::vector<std::string>{"zoo", "giraffe", "tri", "zebra", "mirror"}));
}

TEST(MeshFormats, GlbReadsLikeItsGltf) {
    TempDir tmp;
    const std::string bytes = glb_bytes();
    check_zoo(read_mesh(tmp.write("zoo.glb", bytes)), tmp.path().string());
}

TEST(MeshFormats, TruncatedGlbIsAnInputErrorNamingTheFile) {
    TempDir tmp;
    const std::string bytes = glb_bytes();
    const std::string p = tmp.write("cut.glb", bytes.substr(0, bytes.size() / 2));
    const std::string e = error_of(p);
    EXPECT_NE(e.find(p + ": "), std::string::npos) << e;
}

TEST(MeshFormats, GltfWithPointsOnlyIsRefusedSayingSo) {
    TempDir tmp;
    const std::string b = gltf_buffer();
    std::string json =
        gltf_json("data:application/octet-stream;base64," + base64(b), b.size());
    json.replace(json.find("\"material\": 0"), 13, "\"mode\": 0");
    const std::string p = tmp.write("points.gltf", json);
    EXPECT_EQ(error_of(p),
              p + ": the file holds no triangles (only 9 points and 0 lines)");
}

TEST(MeshFormats, ObjectsAreSelectedByNodeOrMeshName) {
    TempDir tmp;
    const std::string p = write_gltf(tmp);
    MeshLoadReport r;
    const TriangleMesh giraffe = load_mesh(p + "#giraffe", &r);
    ASSERT_EQ(giraffe.num_triangles(), 1u);
    EXPECT_EQ(r.read.pieces_read, 1u);
    EXPECT_NEAR(giraffe.surface_area(), 2.0, 1e-9);  // scaled by 2: area x4
    expect_near(giraffe.bounds().lo, {10, 0, 0});
    // A node selects its subtree; the mesh name selects every instance of the mesh.
    EXPECT_EQ(load_mesh(p + "#zoo").num_triangles(), 3u);
    EXPECT_EQ(load_mesh(p + "#tri").num_triangles(), 3u);
    const std::string e = error_of(p + "#okapi");
    EXPECT_NE(e.find(p + ": no object named \"okapi\""), std::string::npos) << e;
    EXPECT_NE(e.find("\"zoo\", \"giraffe\", \"tri\", \"zebra\", \"mirror\""),
              std::string::npos)
        << e;
}

TEST(MeshFormats, MergingSeveralObjectsSaysSoOncePerFile) {
    TempDir tmp;
    const std::string p = write_gltf(tmp);
    testing::internal::CaptureStderr();
    (void)load_mesh(p);
    (void)load_mesh(p);
    (void)load_mesh(p + "#giraffe");
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find(p + ": merged its 3 objects into one mesh"), std::string::npos)
        << err;
    EXPECT_EQ(err.find("merged"), err.rfind("merged")) << err;
}

// A unit square (two triangles after triangulation) and a triangle of area 2.
const char *ply_ascii =
    "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 7\n"
    "property float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 5\n2 0 5\n0 2 5\n4 0 1 2 3\n3 4 5 6\n";

TEST(MeshFormats, AssimpPrintsNothingAndReadsDeterministically) {
    TempDir tmp;
    const std::string good = write_gltf(tmp);
    const std::string bad = tmp.write("bad.gltf", "{\"asset\": {\"version\": \"2.0\"");
    std::string cut = ply_ascii;
    cut.resize(cut.size() / 2);
    const std::string bad_ply = tmp.write("cut.ply", cut);
    const std::string points = tmp.write(
        "points.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
        "y\nproperty float z\nend_header\n0 0 0\n");
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const TriangleMesh a = read_mesh(good), b = read_mesh(good);
    EXPECT_THROW((void)read_mesh(bad), InputError);
    EXPECT_THROW((void)read_mesh(bad_ply), InputError);
    EXPECT_THROW((void)read_mesh(points), InputError);
    const std::string out = testing::internal::GetCapturedStdout();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(out, "");
    EXPECT_EQ(err, "");
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.corner_normals, b.corner_normals);
}

TEST(MeshFormats, PlyAsciiAndBinaryGiveTheKnownTriangles) {
    TempDir tmp;
    std::string bin =
        "ply\nformat binary_little_endian 1.0\nelement vertex 7\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    append<float>(&bin, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 5, 2, 0, 5, 0, 2, 5});
    append<uint8_t>(&bin, {4});
    append<int32_t>(&bin, {0, 1, 2, 3});
    append<uint8_t>(&bin, {3});
    append<int32_t>(&bin, {4, 5, 6});
    // The same as big-endian: every value's bytes reversed.
    std::string big = bin;
    big.replace(big.find("binary_little_endian"), 20, "binary_big_endian");
    for (size_t at = big.find("end_header\n") + 11, i = 0; i < 21; ++i, at += 4)
        std::reverse(big.begin() + long(at), big.begin() + long(at) + 4);
    for (size_t at = big.size() - 30, f = 0; f < 2; ++f) {  // "4 0 1 2 3", "3 4 5 6"
        at += 1;
        const int n = f == 0 ? 4 : 3;
        for (int k = 0; k < n; ++k, at += 4)
            std::reverse(big.begin() + long(at), big.begin() + long(at) + 4);
    }
    for (const std::string &p : {tmp.write("a.ply", ply_ascii), tmp.write("b.ply", bin),
                                 tmp.write("c.ply", big)}) {
        SCOPED_TRACE(p);
        const TriangleMesh m = load_mesh(p);
        ASSERT_EQ(m.num_triangles(), 3u);
        EXPECT_NEAR(m.surface_area(), 3.0, 1e-12);
        const Bounds3 box = m.bounds();
        expect_near(box.lo, {0, 0, 0});
        expect_near(box.hi, {2, 2, 5});
        // The triangle keeps its corners and their order.
        expect_triangle(m, 2, {0, 0, 5}, {2, 0, 5}, {0, 2, 5});
        EXPECT_TRUE(m.corner_normals.empty());
        EXPECT_TRUE(m.materials.empty());
    }
}

TEST(MeshFormats, PlyNormalsAndUvsBecomeCornerAttributes) {
    TempDir tmp;
    const std::string p = tmp.write(
        "n.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
        "property double z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "property float s\nproperty float t\nproperty uchar red\n"
        "element face 1\nproperty uchar flags\nproperty list uint8 uint32 vertex_index\n"
        "element edge 1\nproperty int a\nproperty int b\nend_header\n"
        "0 0 0 0 0 1 0 0 255\n1 0 0 0 0 1 1 0 0\n0 1 0 0 0 1 0 1 7\n9 3 0 2 1\n0 1\n");
    const TriangleMesh m = read_mesh(p);
    ASSERT_EQ(m.num_triangles(), 1u);
    EXPECT_EQ(m.triangles[0], (std::array<VertId, 3>{0, 2, 1}));
    ASSERT_EQ(m.corner_normals.size(), 3u);
    EXPECT_EQ(m.corner_normals[1], (Vec3d{0, 0, 1}));
    ASSERT_EQ(m.corner_uvs.size(), 3u);
    EXPECT_EQ(m.corner_uvs[1], (Vec2d{0, 1}));
    EXPECT_EQ(m.corner_uvs[2], (Vec2d{1, 0}));
}

TEST(MeshFormats, BadPlyFilesAreInputErrors) {
    TempDir tmp;
    std::string out_of_range = ply_ascii;
    out_of_range.replace(out_of_range.find("3 4 5 6"), 7, "3 4 5 9");
    std::string nan = ply_ascii;
    nan.replace(nan.find("2 0 5"), 5, "nan 0 5");
    const std::string points_only =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
        "y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    const std::string ascii = ply_ascii;
    const struct {
        std::string name, contents, message;
    } cases[] = {
        {"range.ply", out_of_range, ":19: face 1: vertex index 9 out of range [0, 7)"},
        {"nan.ply", nan, ":16: vertex 5: non-finite coordinate"},
        {"points.ply", points_only,
         ": the file holds no triangles (only 3 points: no faces)"},
        {"empty.ply", "", ": empty file"},
        {"cut.ply", ascii.substr(0, ascii.find("4 0 1 2 3")),
         ":17: truncated file: expected 2 face rows, found 0"},
        {"short.ply", std::string(ascii).replace(ascii.find("\n1 0 0\n") + 1, 5, "1 0"),
         ":12: vertex 1: too few values on the line"},
        {"long.ply",
         std::string(ascii).replace(ascii.find("\n1 0 0\n") + 1, 5, "1 0 0 0"),
         ":12: vertex 1: 4 values on the line, the header's properties take 3"},
        {"type.ply", std::string(ascii).replace(ascii.find("float x"), 5, "flaot"),
         ":5: unknown property type 'flaot'"},
        {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n",
         ":4: truncated header: no end_header line"},
        {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n",
         ":3: element 'vertex' declares 99999999999 rows, more than a file of"},
    };
    for (const auto &c : cases) {
        const std::string p = tmp.write(c.name, c.contents);
        const std::string e = error_of(p);
        EXPECT_EQ(e.rfind(p + c.message, 0), 0u) << e;
    }
    // Binary: the element, not a line, is named.
    std::string bin =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    append<float>(&bin, {0, 0, 0, 1, 0, 0, 0, 1, 0});
    append<uint8_t>(&bin, {3});
    append<int32_t>(&bin, {0, 1, 3});
    EXPECT_EQ(error_of(tmp.write("b.ply", bin)),
              tmp.file("b.ply") + ": face 0: vertex index 3 out of range [0, 3)");
    bin.resize(bin.size() - 6);
    EXPECT_EQ(error_of(tmp.write("c.ply", bin)),
              tmp.file("c.ply") + ": truncated file: the data ends inside face 0");
    EXPECT_NE(error_of(tmp.file("missing.ply")).find("cannot open file"),
              std::string::npos);
}

// assimp's exporter writes a mesh of known positions as Collada and FBX; reading them
// back must give the same positions (the exporter is another implementation than the
// importer, and the mesh is the reference).
TEST(MeshFormats, ColladaAndFbxRoundTripAKnownMesh) {
    const float pos[4][3] = {{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {0, 0, 1.5f}};
    const unsigned faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    auto scene = std::make_unique<aiScene>();
    scene->mRootNode = new aiNode("root");
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial *[1] { new aiMaterial() };
    auto *mesh = new aiMesh();
    mesh->mName = "tetra";
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = 4;
    mesh->mVertices = new aiVector3D[4];
    for (int v = 0; v < 4; ++v) mesh->mVertices[v] = {pos[v][0], pos[v][1], pos[v][2]};
    mesh->mNumFaces = 4;
    mesh->mFaces = new aiFace[4];
    for (int f = 0; f < 4; ++f) {
        mesh->mFaces[f].mNumIndices = 3;
        mesh->mFaces[f].mIndices = new unsigned[3]{faces[f][0], faces[f][1], faces[f][2]};
    }
    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh *[1] { mesh };

    TempDir tmp;
    Assimp::Exporter exporter;
    for (const auto &[format, ext] : {std::pair{"collada", "dae"}, {"fbxa", "fbx"}}) {
        SCOPED_TRACE(format);
        const std::string p = tmp.file(std::string("tetra.") + ext);
        ASSERT_EQ(exporter.Export(scene.get(), format, p), aiReturn_SUCCESS)
            << exporter.GetErrorString();
        const TriangleMesh m = load_mesh(p);
        ASSERT_EQ(m.num_triangles(), 4u);
        // Each face of the reference appears with its corners in order (up to rotation).
        for (const auto &f : faces) {
            bool found = false;
            for (TriId t = 0; t < 4 && !found; ++t)
                for (int r = 0; r < 3 && !found; ++r) {
                    bool same = true;
                    for (int c = 0; c < 3; ++c) {
                        const float *q = pos[f[c]];
                        const Vec3d v = m.vertex(t, (c + r) % 3);
                        same &= std::abs(v.x - q[0]) < 1e-5 &&
                                std::abs(v.y - q[1]) < 1e-5 &&
                                std::abs(v.z - q[2]) < 1e-5;
                    }
                    found = same;
                }
            EXPECT_TRUE(found) << "face " << f[0] << " " << f[1] << " " << f[2];
        }
        EXPECT_NEAR(m.surface_area(), load_mesh(p).surface_area(), 0);
    }
}

TEST(MeshFormats, ObjObjectsAndGroupsAreSelectable) {
    TempDir tmp;
    const std::string p = tmp.write("zoo.obj",
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                    "f 1 2 3\n"  // before any name
                                    "o giraffe\ng body\nf 1 2 3\nf 2 4 3\n"
                                    "g head neck\nf 1 2 4\n"
                                    "o zebra \r\ng\nf 1 3 4\n");
    MeshReadStats st;
    EXPECT_EQ(read_mesh(p, &st).num_triangles(), 5u);
    EXPECT_EQ(st.object_names,
              (std::vector<std::string>{"giraffe", "body", "head", "neck", "zebra"}));
    EXPECT_EQ(st.pieces_read, 4u);  // unnamed, giraffe/body, giraffe/head neck, zebra
    const TriangleMesh giraffe = read_mesh(p, &st, "giraffe");
    ASSERT_EQ(giraffe.num_triangles(), 3u);
    EXPECT_EQ(giraffe.source_face, (std::vector<uint32_t>{1, 2, 3}));
    EXPECT_EQ(st.pieces_read, 2u);
    EXPECT_EQ(read_mesh(p, nullptr, "body").source_face, (std::vector<uint32_t>{1, 2}));
    EXPECT_EQ(read_mesh(p, nullptr, "neck").source_face, (std::vector<uint32_t>{3}));
    EXPECT_EQ(read_mesh(p, nullptr, "zebra").source_face, (std::vector<uint32_t>{4}));
    const std::string e = error_of(p + "#okapi");
    EXPECT_NE(e.find("no object named \"okapi\" (the file's objects: \"giraffe\", "
                     "\"body\", \"head\", \"neck\", \"zebra\")"),
              std::string::npos)
        << e;
    const std::string off =
        tmp.write("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_NE(error_of(off + "#x").find("a .off file holds one unnamed object"),
              std::string::npos);
}

TEST(MeshFormats, ObjMaterialsComeFromTheMtlWithTexturesResolvedAgainstIt) {
    TempDir tmp;
    std::filesystem::create_directories(tmp.path() / "mats");
    tmp.write("mats/zoo.mtl",
              "newmtl tan\nKd 0.8 0.6 0.3\nmap_Kd ../tex/tan.png\n"
              "newmtl dark\nKd 0.1 0.05 0.02\n");
    const std::string p = tmp.write("zoo.obj",
                                    "mtllib mats/zoo.mtl\n"
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\n"
                                    "f 1 2 3\n"
                                    "usemtl dark\nf 2 4 3\nf 1 2 5\n"  // f 1 2 5 is flat
                                    "usemtl tan\nf 1 2 4 3\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    ASSERT_EQ(m.materials.size(), 2u);
    EXPECT_EQ(m.materials[0].name, "tan");
    expect_near(m.materials[0].diffuse, {0.8, 0.6, 0.3});
    EXPECT_EQ(m.materials[0].diffuse_texture, (tmp.path() / "tex/tan.png").string());
    EXPECT_EQ(m.materials[1].name, "dark");
    EXPECT_EQ(m.materials[1].diffuse_texture, "");
    // The degenerate triangle is dropped; the materials stay with their triangles.
    EXPECT_EQ(r.clean.degenerate_dropped, 1u);
    EXPECT_EQ(m.triangle_material, (std::vector<uint32_t>{invalid_id, 1, 0, 0}));
    EXPECT_EQ(m.source_face, (std::vector<uint32_t>{0, 1, 3, 3}));
}

TEST(MeshFormats, MeshSpecsSplitAfterAMeshExtension) {
    EXPECT_EQ(parse_mesh_spec("a/zoo.glb#giraffe").path, "a/zoo.glb");
    EXPECT_EQ(parse_mesh_spec("a/zoo.glb#giraffe").object, "giraffe");
    EXPECT_EQ(parse_mesh_spec("a/ZOO.OBJ#x#y").object, "x#y");
    EXPECT_EQ(parse_mesh_spec("take#2/zoo.off").path, "take#2/zoo.off");
    EXPECT_EQ(parse_mesh_spec("take#2/zoo.fbx#a").path, "take#2/zoo.fbx");
    EXPECT_EQ(parse_mesh_spec("notes.txt#x").path, "notes.txt#x");
    EXPECT_EQ(parse_mesh_spec("zoo.glb").object, "");
    EXPECT_THROW((void)parse_mesh_spec("zoo.glb#"), InputError);
    EXPECT_TRUE(is_mesh_extension("GLB"));
    EXPECT_TRUE(is_mesh_extension("ply"));
    EXPECT_FALSE(is_mesh_extension("txt"));
    EXPECT_FALSE(is_mesh_extension(""));
}

}  // namespace
}  // namespace pelage::sim
