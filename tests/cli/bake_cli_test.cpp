// `pelage bake` end to end. A texture render of the bake agrees with the clonal_mosaic
// render of the same scene at the bake's resolution (one pixel about one texel), both
// on the mesh's own UVs over six UDIM tiles and on the packed atlas; the exported OBJ
// keeps the input's UVs and normals; bad inputs exit 2 naming file and field.
//
// Agreement: the first-hit albedo layers of the two renders (one sample per pixel, so
// the mosaic is blended over a one-pixel footprint at the sample, the bake over a
// one-texel footprint; lighting and sample positions are identical, the sampler's
// sequences depend on the pixel only) differ by less than 0.1 in every channel: an
// eighth of the two cell types' contrast (0.8 in red). Away from cell edges both are a
// cell's colour exactly. Across an edge the blend runs from one colour to the other
// over about a texel, and the texture interpolates it linearly between texel centres: a
// curve that bends that much within a texel departs from its chord by up to about an
// eighth of its rise (h² f''/8), and the footprints of pixel and texel differ somewhat
// over the curved surface. 99 % of the object's pixels must agree.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::vector<float> read_layer(const std::string &path, const std::string &prefix,
                              int *width, int *height) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> all(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, all.data());
    std::vector<int> ch;
    for (const char *c : {"R", "G", "B"})
        for (int k = 0; k < s.nchannels; ++k)
            if (s.channelnames[k] == prefix + c) ch.push_back(k);
    if (ch.size() != 3) return {};
    *width = s.width;
    *height = s.height;
    std::vector<float> out;
    for (size_t i = 0; i < size_t(s.width) * s.height; ++i)
        for (int k : ch) out.push_back(all[i * s.nchannels + k]);
    return out;
}

// A sphere whose UVs are a cube map: each triangle goes to the cube face of its normal,
// one UDIM tile per face (1001-1003, 1011-1013), by the angles of its projection onto
// the face; smooth normals.
std::string write_cube_mapped_sphere(const TempDir &tmp, int level = 3) {
    const std::string path = tmp.file("sphere" + std::to_string(level) + ".obj");
    const sim::TriangleMesh m =
        sim::load_mesh("procedural:icosphere:" + std::to_string(level));
    std::ofstream out(path);
    out.precision(17);
    for (const auto &p : m.positions)
        out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (size_t t = 0; t < m.num_triangles(); ++t) {
        const sim::Vec3d c = (m.vertex(t, 0) + m.vertex(t, 1) + m.vertex(t, 2)) / 3;
        const double a[3] = {std::abs(c.x), std::abs(c.y), std::abs(c.z)};
        const int axis = a[0] >= a[1] && a[0] >= a[2] ? 0 : (a[1] >= a[2] ? 1 : 2);
        const int face = 2 * axis + (c[axis] < 0);
        for (int k = 0; k < 3; ++k) {
            const sim::Vec3d p = m.vertex(t, k);
            const double d = std::abs(p[axis]);
            const double s = p[(axis + 1) % 3] / d, r = p[(axis + 2) % 3] / d;
            // Equal-angle: atan keeps corners past the face's edge inside the tile.
            out << "vt " << (face % 3) + 0.5 + 0.3 * std::atan(s) << " "
                << (face / 3) + 0.5 + 0.3 * std::atan(r) << "\n";
        }
    }
    for (const auto &p : m.positions) {
        const sim::Vec3d n = normalize(p);
        out << "vn " << n.x << " " << n.y << " " << n.z << "\n";
    }
    for (size_t t = 0; t < m.num_triangles(); ++t) {
        out << "f";
        for (int k = 0; k < 3; ++k)
            out << " " << m.triangles[t][k] + 1 << "/" << 3 * t + k + 1 << "/"
                << m.triangles[t][k] + 1;
        out << "\n";
    }
    return path;
}

std::string scene(const std::string &mesh, const std::string &material,
                  const std::string &cells, int res) {
    return R"({"camera": {"position": [0, 0.6, 3.4], "look_at": [0, 0, 0], "fov": 40},
  "film": {"width": )" +
           std::to_string(res) + R"(, "height": )" + std::to_string(res) +
           R"(, "spp": 1},
  "lights": [{"type": "environment", "color": [0.8, 0.8, 0.8]}],
  "objects": [{"mesh": ")" +
           mesh + R"(", "normals": "smooth", )" +
           (cells.empty() ? "" : "\"cells\": \"" + cells + "\", ") + R"("material": )" +
           material + "}]}";
}

// The share of object pixels whose albedo agrees within `tol` in every channel.
double agreement(const std::string &a, const std::string &b, double tol, size_t *object) {
    int w = 0, h = 0, w2 = 0, h2 = 0;
    const std::vector<float> pa = read_layer(a, "albedo.", &w, &h),
                             pb = read_layer(b, "albedo.", &w2, &h2);
    EXPECT_FALSE(pa.empty());
    EXPECT_EQ(pa.size(), pb.size());
    if (pa.empty() || pa.size() != pb.size()) return 0;
    size_t agree = 0, n = 0;
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        const float *x = &pa[3 * i], *y = &pb[3 * i];
        if (x[0] + x[1] + x[2] == 0 && y[0] + y[1] + y[2] == 0) continue;  // background
        ++n;
        agree += std::max({std::abs(x[0] - y[0]), std::abs(x[1] - y[1]),
                           std::abs(x[2] - y[2])}) < tol;
    }
    *object = n;
    return n ? double(agree) / double(n) : 0;
}

TEST(BakeCli, UdimBakeOnTheMeshsUvsRendersLikeTheMosaic) {
    TempDir tmp;
    const std::string mesh = write_cube_mapped_sphere(tmp);
    const std::string cells = simulate_two_type_cells(tmp, mesh, 400, 0.4);
    std::string out, err;
    ASSERT_EQ(run_pelage("bake " + cells + " --uv-from " + mesh + " --res 384 -o " + "'" +
                             tmp.file("tex.<UDIM>.exr") + "'" + " --obj " +
                             tmp.file("baked.obj") + " --stats-json " +
                             tmp.file("stats.json") + " -q",
                         &out, &err),
              0)
        << err;
    EXPECT_TRUE(out.empty()) << out;
    const auto stats = nlohmann::json::parse(std::ifstream(tmp.file("stats.json")));
    ASSERT_EQ(stats["tiles"].size(), 6u) << stats.dump();
    for (int udim : {1001, 1002, 1003, 1011, 1012, 1013})
        EXPECT_TRUE(
            std::filesystem::exists(tmp.file("tex." + std::to_string(udim) + ".exr")))
            << udim;
    EXPECT_GT(stats["coverage"].get<double>(), 0.15);  // a disc-like chart per tile

    // The exported mesh keeps the input's UVs and normals (to the last digits the OBJ
    // reader's number parsing keeps: it is not correctly rounded).
    const sim::TriangleMesh in = sim::load_mesh(mesh),
                            baked = sim::load_mesh(tmp.file("baked.obj"));
    ASSERT_EQ(in.num_triangles(), baked.num_triangles());
    ASSERT_EQ(in.corner_uvs.size(), baked.corner_uvs.size());
    ASSERT_EQ(in.corner_normals.size(), baked.corner_normals.size());
    ASSERT_FALSE(baked.corner_normals.empty());
    for (size_t i = 0; i < in.corner_uvs.size(); ++i) {
        ASSERT_LT(length(in.corner_uvs[i] - baked.corner_uvs[i]), 1e-12) << i;
        ASSERT_LT(length(in.corner_normals[i] - baked.corner_normals[i]), 1e-12) << i;
    }
    for (size_t i = 0; i < in.positions.size(); ++i)
        ASSERT_LT(length(in.positions[i] - baked.positions[i]), 1e-12) << i;

    // A pixel about a texel at the sphere's front: a tile maps 0.3 radians of arc to its
    // width (u = 0.5 + 0.3 atan s), so a texel is 1 / (0.3 · 384) = 0.0087 units of the
    // unit sphere; a pixel 2.43 units away is 2 · 2.43 · tan 20° / 192 = 0.0092.
    const int res = 192;
    const std::string mosaic = tmp.write(
        "mosaic.json", scene(mesh, R"({"shader": "clonal_mosaic"})", cells, res));
    const std::string texture =
        tmp.write("texture.json", scene(tmp.file("baked.obj"),
                                        R"({"shader": "texture", "params": {"file": ")" +
                                            tmp.file("tex.<UDIM>.exr") + R"("}})",
                                        "", res));
    ASSERT_EQ(run_pelage("render " + mosaic + " -o " + tmp.file("m.exr"), nullptr, &err),
              0)
        << err;
    ASSERT_EQ(run_pelage("render " + texture + " -o " + tmp.file("t.exr"), nullptr, &err),
              0)
        << err;
    size_t object = 0;
    const double share = agreement(tmp.file("m.exr"), tmp.file("t.exr"), 0.1, &object);
    EXPECT_GT(object, size_t(res * res / 4));
    EXPECT_GE(share, 0.99) << object << " object pixels";
}

TEST(BakeCli, AtlasBakeRendersLikeTheMosaic) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 400, 0.4);
    std::string out, err;
    ASSERT_EQ(run_pelage("bake " + cells + " --mesh " + mesh + " --res 512x512 -o " +
                             tmp.file("atlas.exr") + " --obj " + tmp.file("atlas.obj") +
                             " --stats-json " + tmp.file("stats.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_NE(out.find("charts"), std::string::npos) << out;
    const auto stats = nlohmann::json::parse(std::ifstream(tmp.file("stats.json")));
    EXPECT_EQ(stats["layout"], "atlas");
    EXPECT_GT(stats["coverage"].get<double>(), 0.5);
    const double tpu = stats["texels_per_unit"].get<double>();
    // A pixel about a texel at the sphere's front (2.3 units away, fov 40°).
    const int res = int(2 * 2.3 * std::tan(20 * M_PI / 180) * tpu);
    const std::string mosaic = tmp.write(
        "mosaic.json", scene(mesh, R"({"shader": "clonal_mosaic"})", cells, res));
    const std::string texture =
        tmp.write("texture.json", scene(tmp.file("atlas.obj"),
                                        R"({"shader": "texture", "params": {"file": ")" +
                                            tmp.file("atlas.exr") + R"("}})",
                                        "", res));
    ASSERT_EQ(run_pelage("render " + mosaic + " -o " + tmp.file("m.exr"), nullptr, &err),
              0)
        << err;
    ASSERT_EQ(run_pelage("render " + texture + " -o " + tmp.file("t.exr"), nullptr, &err),
              0)
        << err;
    size_t object = 0;
    const double share = agreement(tmp.file("m.exr"), tmp.file("t.exr"), 0.1, &object);
    EXPECT_GT(object, size_t(res * res / 4));
    EXPECT_GE(share, 0.99) << object << " object pixels at " << res << "x" << res;
}

// The cells grown on one triangulation of the sphere, baked into the UVs of a finer
// one (carried onto the simulation surface like a render of that mesh), at one and two
// threads alike.
TEST(BakeCli, UvsOfAnotherTriangulationOfTheShape) {
    TempDir tmp;
    const std::string cells =
        simulate_two_type_cells(tmp, "procedural:icosphere:3", 400, 0.4);
    const std::string mesh = write_cube_mapped_sphere(tmp, 4);
    std::string err;
    for (int threads : {1, 2})
        ASSERT_EQ(run_pelage("bake " + cells + " --uv-from " + mesh + " --res 384 -o '" +
                                 tmp.file("t" + std::to_string(threads) + ".<UDIM>.exr") +
                                 "' -q --threads " + std::to_string(threads),
                             nullptr, &err),
                  0)
            << err;
    for (int udim : {1001, 1002, 1003, 1011, 1012, 1013}) {
        int w, h, w2, h2;
        const auto a = read_layer(tmp.file("t1." + std::to_string(udim) + ".exr"), "", &w,
                                  &h),
                   b = read_layer(tmp.file("t2." + std::to_string(udim) + ".exr"), "",
                                  &w2, &h2);
        ASSERT_FALSE(a.empty());
        EXPECT_TRUE(a == b) << udim;
    }
    const int res = 192;
    const std::string mosaic = tmp.write(
        "mosaic.json", scene(mesh, R"({"shader": "clonal_mosaic"})", cells, res));
    const std::string texture =
        tmp.write("texture.json", scene(mesh,
                                        R"({"shader": "texture", "params": {"file": ")" +
                                            tmp.file("t1.<UDIM>.exr") + R"("}})",
                                        "", res));
    ASSERT_EQ(run_pelage("render " + mosaic + " -o " + tmp.file("m.exr"), nullptr, &err),
              0)
        << err;
    ASSERT_EQ(run_pelage("render " + texture + " -o " + tmp.file("t.exr"), nullptr, &err),
              0)
        << err;
    size_t object = 0;
    const double share = agreement(tmp.file("m.exr"), tmp.file("t.exr"), 0.1, &object);
    EXPECT_GT(object, size_t(res * res / 4));
    EXPECT_GE(share, 0.99) << object << " object pixels";

    // The atlas of that finer mesh: laid out from it, its triangles in the OBJ.
    ASSERT_EQ(run_pelage("bake " + cells + " --mesh " + mesh + " --res 256 -q -o " +
                             tmp.file("a.exr") + " --obj " + tmp.file("a.obj"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_EQ(sim::load_mesh(tmp.file("a.obj")).num_triangles(),
              sim::load_mesh(mesh).num_triangles());
}

TEST(BakeCli, OverlappingUvsAreAWarningWithTheirShare) {
    TempDir tmp;
    const std::string mesh = write_cube_mapped_sphere(tmp);
    const std::string cells = simulate_two_type_cells(tmp, mesh, 200, 0.4);
    // Every cube face's UVs moved into tile 1001: six charts on top of each other.
    std::ifstream in(mesh);
    std::ofstream stacked(tmp.file("stacked.obj"));
    for (std::string line; std::getline(in, line);) {
        double u, v;
        if (std::sscanf(line.c_str(), "vt %lf %lf", &u, &v) == 2)
            stacked << "vt " << u - std::floor(u) << " " << v - std::floor(v) << "\n";
        else
            stacked << line << "\n";
    }
    stacked.close();
    std::string err;
    ASSERT_EQ(run_pelage("bake " + cells + " --uv-from " + tmp.file("stacked.obj") +
                             " --res 64 -o " + tmp.file("s.exr"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_NE(err.find("overlapping UVs"), std::string::npos) << err;
    EXPECT_NE(err.find("stacked.obj"), std::string::npos) << err;
    EXPECT_NE(err.find(" %"), std::string::npos) << err;
}

TEST(BakeCli, BadInputsExitTwoNamingFileAndField) {
    TempDir tmp;
    const std::string mesh = write_cube_mapped_sphere(tmp);
    const std::string cells = simulate_two_type_cells(tmp, mesh, 200, 0.4);
    std::string err;
    // A mesh without UVs.
    EXPECT_EQ(run_pelage("bake " + cells + " --uv-from procedural:icosphere:3 -o " +
                             tmp.file("x.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("procedural:icosphere:3"), std::string::npos) << err;
    EXPECT_NE(err.find("vt"), std::string::npos) << err;
    // Several tiles but no <UDIM> in the name.
    EXPECT_EQ(run_pelage("bake " + cells + " --uv-from " + mesh + " --res 32 -o " +
                             tmp.file("x.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("<UDIM>"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.exr")));
    // UVs beyond tile 1100: the same sphere with u moved ten tiles right.
    std::ifstream in(mesh);
    std::ofstream far(tmp.file("far.obj"));
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("vt ", 0) == 0) {
            double u, v;
            std::sscanf(line.c_str(), "vt %lf %lf", &u, &v);
            far << "vt " << u + 10 << " " << v << "\n";
        } else {
            far << line << "\n";
        }
    }
    far.close();
    EXPECT_EQ(run_pelage("bake " + cells + " --uv-from " + tmp.file("far.obj") +
                             " --res 32 -o " + "'" + tmp.file("y.<UDIM>.exr") + "'",
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("far.obj"), std::string::npos) << err;
    EXPECT_NE(err.find("1001-1100"), std::string::npos) << err;
    // Neither --mesh nor --uv-from; a resolution that is not one.
    EXPECT_EQ(run_pelage("bake " + cells + " -o " + tmp.file("z.exr"), nullptr, &err), 2);
    EXPECT_EQ(run_pelage("bake " + cells + " --mesh " + mesh + " --res 64y -o " +
                             tmp.file("z.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("--res"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
