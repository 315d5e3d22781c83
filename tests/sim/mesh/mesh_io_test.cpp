// Mesh reading and cleaning: formats, triangulation, welding, degenerate faces, and the
// line numbers in errors.
#include <gtest/gtest.h>

#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

using test::TempDir;

// Returns the line the InputError names, or 0 when nothing was thrown.
size_t error_line(const std::string &path) {
    try {
        (void)load_mesh(path);
    } catch (const InputError &e) {
        return e.line();
    }
    return 0;
}

TEST(MeshIo, OffWithCommentsCountsOnHeaderAndAQuad) {
    TempDir tmp;
    const auto p =
        tmp.write("q.off",
                  "OFF 4 1 0  # header and counts on one line\n"
                  "\n0 0 0\n1 0 0 # extras are fine\n1 1 0 0.5 0.5 0.5\n0 1 0\n"
                  "4 0 1 2 3  255 0 0\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    EXPECT_EQ(m.num_vertices(), 4u);
    ASSERT_EQ(m.num_triangles(), 2u);
    EXPECT_EQ(r.read.polygons_triangulated, 1u);
    EXPECT_EQ(m.source_face[0], 0u);
    EXPECT_EQ(m.source_face[1], 0u);
    EXPECT_DOUBLE_EQ(m.surface_area(), 1.0);
}

TEST(MeshIo, ObjWithNormalsUvsNegativeIndicesAndAQuad) {
    TempDir tmp;
    const auto p = tmp.write("q.obj",
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                             "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                             "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
                             "f -4/1/1 -2/3/1 -1/4/1\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    EXPECT_EQ(m.num_triangles(), 3u);
    ASSERT_EQ(m.corner_normals.size(), 9u);
    ASSERT_EQ(m.corner_uvs.size(), 9u);
    EXPECT_EQ(m.corner_normals[0], (Vec3d{0, 0, 1}));
    EXPECT_EQ(m.corner_uvs[1], (Vec2d{1, 0}));
    EXPECT_EQ(r.read.polygons_triangulated, 1u);
    EXPECT_EQ(m.source_face[2], 1u);
}

TEST(MeshIo, DuplicateVerticesAreWeldedRelativeToTheBox) {
    TempDir tmp;
    // Two triangles stored as separate corners: welding must join them along an edge.
    const auto p = tmp.write("w.off",
                             "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n1 0 1e-9\n1 1 0\n0 1 0\n"
                             "3 0 1 2\n3 3 4 5\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    EXPECT_EQ(r.clean.vertices_welded, 2u);
    EXPECT_EQ(m.num_vertices(), 4u);
    EXPECT_EQ(m.triangles[1][0], 1u);
    EXPECT_EQ(m.triangles[1][2], 2u);
}

// The weld is relative to what the triangles use: a file's reader may keep every vertex
// of a scene for one of its objects, and a unit quad must not be welded at the scale of
// a vertex 1e8 away (10 units at 1e-7 of that box's diagonal: the quad would vanish).
// Copies of a corner 2e-6 apart (an export's rounding) are welded at 1e-5 of the quad's.
TEST(MeshIo, TheWeldIsRelativeToTheVerticesTrianglesUse) {
    TempDir tmp;
    const auto p = tmp.write("far.off",
                             "OFF\n6 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1e8 0 0\n"
                             "1.000002 1 0\n3 0 1 2\n3 0 5 3\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    EXPECT_EQ(m.num_triangles(), 2u);
    EXPECT_EQ(r.clean.vertices_welded, 1u);  // vertex 5 into vertex 2
    EXPECT_EQ(m.triangles[1][1], m.triangles[0][2]);
    EXPECT_EQ(r.clean.unused_vertices, 1u);  // the far one, kept
}

TEST(MeshIo, DegenerateTrianglesAreDroppedAndCounted) {
    TempDir tmp;
    const auto p = tmp.write("d.off",
                             "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n"
                             "3 0 1 2\n3 0 1 3\n3 1 1 2\n");
    MeshLoadReport r;
    const TriangleMesh m = load_mesh(p, &r);
    EXPECT_EQ(m.num_triangles(), 1u);
    EXPECT_EQ(r.clean.degenerate_dropped, 2u);
    EXPECT_EQ(r.clean.unused_vertices, 1u);
}

TEST(MeshIo, ErrorsNameTheLine) {
    TempDir tmp;
    EXPECT_EQ(
        error_line(tmp.write("a.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n")), 5u);
    EXPECT_EQ(
        error_line(tmp.write("b.off", "OFF\n# c\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")),
        7u);
    EXPECT_EQ(error_line(tmp.write("c.obj", "v 0 0 0\nv 1 0 0\n\nv 0 1 0\nf 1 2 9\n")),
              5u);
    EXPECT_EQ(error_line(tmp.write("d.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n")),
              3u);
}

TEST(MeshIo, HugeLinesAreRejectedWithoutReadingThemWhole) {
    TempDir tmp;
    const std::string long_line(3u << 20, '1');
    EXPECT_EQ(error_line(tmp.write("l.off", "OFF\n3 1 0\n0 0 " + long_line + "\n")), 3u);
    EXPECT_EQ(error_line(tmp.write("l.obj", "v 0 0 0\nv 0 0 " + long_line + "\n")), 2u);
}

TEST(MeshIo, WindowsLineEndingsAreAccepted) {
    TempDir tmp;
    const auto p =
        tmp.write("crlf.off", "OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
    EXPECT_EQ(load_mesh(p).num_triangles(), 1u);
}

TEST(MeshIo, CowAndTriceratopsLoadWithTheirKnownSizes) {
    const TriangleMesh cow = load_mesh(test::sample_mesh("cow.off"));
    EXPECT_EQ(cow.num_triangles(), 5804u);
    const TriangleMesh tri = load_mesh(test::sample_mesh("triceratops.off"));
    EXPECT_EQ(tri.num_triangles(), 5660u);
}

}  // namespace
}  // namespace pelage::sim
