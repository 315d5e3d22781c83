// pelage export's USD read back by an independent reader, TinyUSDZ (npm, WebAssembly;
// tests/export/read_usd.mjs), and compared with what pelage renders: the Scene's own
// strands and meshes, the Cryptomatte ids its fur carries, and a render of the skin.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "renderer/scene_frame/scene_frame.h"
#include "tests/renderer/animation/armature_tube.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool readers_installed() {
    return fs::is_regular_file(fs::path(PELAGE_NODE_MODULES) /
                               "tinyusdz/tinyusdz.wasm") &&
           std::system("node --version >/dev/null 2>&1") == 0;
}

#define REQUIRE_READERS()                                                       \
    if (!readers_installed())                                                   \
    GTEST_SKIP() << "the npm readers are not installed in " PELAGE_NODE_MODULES \
                    " (./quickstart.sh test installs them)"

// What TinyUSDZ read of `usda` (read_usd.mjs's JSON); fails the test when it rejects it.
json read_usd(const TempDir &tmp, const std::string &usda) {
    const std::string out = tmp.file("read.json");
    const std::string cmd = "node " + source_path("tests/export/read_usd.mjs") + " " +
                            PELAGE_NODE_MODULES + " " + usda + " " + out + " 2>" +
                            tmp.file("read.err");
    const int status = std::system(cmd.c_str());
    EXPECT_EQ(status, 0) << slurp(tmp.file("read.err"));
    return json::parse(slurp(out), nullptr, false);
}

std::vector<double> values(const json &prim, const std::string &attr) {
    const json &a = prim.at("attrs").at(attr);
    return a.at("value").get<std::vector<double>>();
}

// The exported transform (USD's row vectors: p' = p · M).
struct UsdMatrix {
    double m[16];
    explicit UsdMatrix(const std::vector<double> &v) { std::copy(v.begin(), v.end(), m); }
    Vec3f apply(double x, double y, double z) const {
        return Vec3f{float(x * m[0] + y * m[4] + z * m[8] + m[12]),
                     float(x * m[1] + y * m[5] + z * m[9] + m[13]),
                     float(x * m[2] + y * m[6] + z * m[10] + m[14])};
    }
    double scale() const {
        const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) -
                           m[1] * (m[4] * m[10] - m[6] * m[8]) +
                           m[2] * (m[4] * m[9] - m[5] * m[8]);
        return std::cbrt(std::abs(det));
    }
};

float distance(Vec3f a, Vec3f b) { return length(a - b); }

// The scene the tests export, written into `tmp` (its cells are grown there).
std::string fur_scene(const TempDir &tmp, const std::string &extra = "") {
    json j = json::parse(slurp(source_path("tests/data/export/fur_sphere.json")));
    if (!extra.empty()) j.merge_patch(json::parse(extra));
    return tmp.write("fur_sphere.json", j.dump(1));
}

int plugin_slot(const renderer::Scene &scene, size_t object, const char *name) {
    const PelageShaderPlugin &p = *scene.materials()[object].plugin;
    for (int k = 0; p.matte_names && k < PELAGE_SHADER_MATTE_SLOTS && p.matte_names[k];
         ++k)
        if (std::string(p.matte_names[k]) == name) return k;
    return -1;
}

TEST(UsdExport, TinyusdzReadsTheCoatPelageRenders) {
    REQUIRE_READERS();
    TempDir tmp;
    const std::string scene_path = fur_scene(tmp);
    const std::string usda = tmp.file("coat.usda");
    std::string err;
    ASSERT_EQ(run_pelage("export " + scene_path + " -q --texture 256 -o " + usda, nullptr,
                         &err),
              0)
        << err;
    const json usd = read_usd(tmp, usda);
    ASSERT_TRUE(usd.is_object());
    EXPECT_EQ(usd["stage"]["defaultPrim"], "coat");
    EXPECT_EQ(usd["stage"]["upAxis"], "Y");
    EXPECT_EQ(usd["stage"]["metersPerUnit"], json::array({1}));
    EXPECT_EQ(usd["stage"]["timeCodesPerSecond"], json::array({24}));

    // The renderer's own scene, its fur carrying Cryptomatte ids per strand.
    renderer::SceneDesc desc = renderer::load_scene_file(scene_path);
    desc.film.cryptomatte = {"type", "cell"};
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    ASSERT_NE(scene.fur(), nullptr);
    const renderer::Strands &st = scene.fur()->layers().at(0).strands;
    const size_t n = st.size(), ppp = st.points_per_strand;
    ASSERT_GT(n, 5000u);

    const json &prims = usd["prims"];
    const UsdMatrix M(values(prims["/coat/sphere"], "xformOp:transform"));
    EXPECT_NEAR(M.scale(), 1.5, 1e-6);

    // --- The fur: every strand, every control point, as Embree traces them ---
    const json &fur = prims["/coat/sphere/fur"];
    EXPECT_EQ(fur["type"], "BasisCurves");
    EXPECT_EQ(fur["attrs"]["type"]["value"], "cubic");
    EXPECT_EQ(fur["attrs"]["basis"]["value"], "bspline");
    const std::vector<double> counts = values(fur, "curveVertexCounts");
    ASSERT_EQ(counts.size(), n);
    EXPECT_TRUE(std::all_of(counts.begin(), counts.end(),
                            [&](double c) { return c == double(ppp); }));
    const std::vector<double> P = values(fur, "points"), W = values(fur, "widths");
    ASSERT_EQ(P.size(), 3 * n * ppp);
    ASSERT_EQ(W.size(), n * ppp);
    EXPECT_EQ(fur["attrs"]["widths"]["interpolation"], "vertex");
    double worst_point = 0, worst_width = 0;
    for (size_t i = 0; i < n * ppp; ++i) {
        const float *R = &st.points[4 * i];
        const Vec3f world = M.apply(P[3 * i], P[3 * i + 1], P[3 * i + 2]);
        worst_point = std::max(worst_point, double(distance(world, {R[0], R[1], R[2]})));
        worst_width = std::max(worst_width, std::abs(W[i] * M.scale() - 2.0 * R[3]));
    }
    EXPECT_LT(worst_point, 2e-6);  // float round-off through the object's transform
    EXPECT_LT(worst_width, 1e-7);

    // Per curve: the cell under the root, as the rendered strand's matte ids name it.
    const int type_slot = plugin_slot(scene, 0, "type"),
              cell_slot = plugin_slot(scene, 0, "cell");
    ASSERT_GE(type_slot, 0);
    ASSERT_GE(cell_slot, 0);
    ASSERT_EQ(st.matte.size(), 4 * n);
    const std::vector<double> type = values(fur, "primvars:cell_type"),
                              cell = values(fur, "primvars:cell_id"),
                              colour = values(fur, "primvars:displayColor"),
                              ids = values(fur, "primvars:groom_id");
    ASSERT_EQ(type.size(), n);
    ASSERT_EQ(cell.size(), n);
    ASSERT_EQ(colour.size(), 3 * n);
    size_t wrong_type = 0, wrong_cell = 0;
    for (size_t s = 0; s < n; ++s) {
        wrong_type += type[s] != double(st.matte[4 * s + size_t(type_slot)]);
        wrong_cell += cell[s] != double(st.matte[4 * s + size_t(cell_slot)]);
        ASSERT_EQ(ids[s], double(s));
    }
    EXPECT_EQ(wrong_type, 0u);
    EXPECT_EQ(wrong_cell, 0u);
    EXPECT_EQ(fur["attrs"]["primvars:cell_type"]["interpolation"], "uniform");
    // Unreal's names carry the same values.
    EXPECT_EQ(values(fur, "primvars:groom_color"), colour);
    EXPECT_EQ(values(fur, "primvars:groom_width"), W);
    EXPECT_EQ(values(fur, "primvars:groom_root_uv"), values(fur, "primvars:root_uv"));
    EXPECT_EQ(values(fur, "primvars:root_uv").size(), 2 * n);

    // --- The skin: the rendered mesh, its triangles in the same order ---
    const json &skin = prims["/coat/sphere/skin"];
    const renderer::MeshData &mesh = *scene.geometry().objects()[0].mesh;
    const std::vector<double> idx = values(skin, "faceVertexIndices"),
                              pts = values(skin, "points");
    ASSERT_EQ(idx.size(), mesh.triangles.size());
    for (size_t i = 0; i < idx.size(); ++i) ASSERT_EQ(idx[i], double(mesh.triangles[i]));
    ASSERT_EQ(pts.size(), 3 * size_t(mesh.num_vertices));
    double worst_vertex = 0;
    for (size_t v = 0; v < mesh.num_vertices; ++v) {
        const float *R = &mesh.positions[3 * v];  // baked: world space
        worst_vertex =
            std::max(worst_vertex,
                     double(distance(M.apply(pts[3 * v], pts[3 * v + 1], pts[3 * v + 2]),
                                     {R[0], R[1], R[2]})));
    }
    EXPECT_LT(worst_vertex, 2e-6);
    EXPECT_EQ(values(skin, "primvars:cell_type").size(), size_t(mesh.num_triangles));
    EXPECT_EQ(skin["attrs"]["subdivisionScheme"]["value"], "none");
    EXPECT_EQ(values(skin, "primvars:st").size(), 6 * size_t(mesh.num_triangles));
    // TinyUSDZ's own conversion of the mesh for rendering found it.
    ASSERT_EQ(usd["meshes"].size(), 1u);
    EXPECT_EQ(usd["meshes"][0]["path"], "/coat/sphere/skin");
    EXPECT_EQ(usd["meshes"][0]["faceVertexCounts"].size(), size_t(mesh.num_triangles));

    // The baked texture, bound through UsdPreviewSurface.
    EXPECT_EQ(skin["attrs"]["material:binding"]["value"], "</coat/sphere/pattern>");
    const json &tex = prims["/coat/sphere/pattern/texture"];
    EXPECT_EQ(tex["attrs"]["info:id"]["value"], "UsdUVTexture");
    const std::string file = tex["attrs"]["inputs:file"]["value"];
    auto in = OIIO::ImageInput::open((tmp.path() / file).string());
    ASSERT_TRUE(in) << file;
    EXPECT_EQ(in->spec().width, 256);
}

// The closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3f closest_on_triangle(Vec3f p, Vec3f a, Vec3f b, Vec3f c) {
    const Vec3f ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3f bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3f cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float den = 1 / (va + vb + vc);
    return a + ab * (vb * den) + ac * (vc * den);
}

// An EXR's channels by name.
struct Exr {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> names;
    std::vector<float> px;
    explicit Exr(const std::string &path) {
        auto in = OIIO::ImageInput::open(path);
        if (!in) return;
        const OIIO::ImageSpec &s = in->spec();
        width = s.width, height = s.height, channels = s.nchannels;
        names = s.channelnames;
        px.resize(size_t(width) * height * channels);
        in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, px.data());
    }
    int channel(const std::string &name) const {
        const auto it = std::find(names.begin(), names.end(), name);
        return it == names.end() ? -1 : int(it - names.begin());
    }
    float at(int x, int y, int c) const {
        return px[(size_t(y) * width + x) * channels + size_t(c)];
    }
};

TEST(UsdExport, FurRootsLieOnTheSkinInTheCellsPelageRendersThere) {
    REQUIRE_READERS();
    TempDir tmp;
    const std::string scene_path = fur_scene(tmp);
    const std::string usda = tmp.file("coat.usda");
    std::string err;
    ASSERT_EQ(run_pelage("export " + scene_path + " -q -o " + usda, nullptr, &err), 0)
        << err;
    const json usd = read_usd(tmp, usda);
    const json &prims = usd["prims"];
    const UsdMatrix M(values(prims["/coat/sphere"], "xformOp:transform"));
    const std::vector<double> sp = values(prims["/coat/sphere/skin"], "points"),
                              si =
                                  values(prims["/coat/sphere/skin"], "faceVertexIndices");
    const json &fur = prims["/coat/sphere/fur"];
    const std::vector<double> P = values(fur, "points"),
                              counts = values(fur, "curveVertexCounts"),
                              colour = values(fur, "primvars:displayColor"),
                              cell = values(fur, "primvars:cell_id");
    auto skin_point = [&](size_t v) {
        return Vec3f{float(sp[3 * v]), float(sp[3 * v + 1]), float(sp[3 * v + 2])};
    };
    Vec3f lo = skin_point(0), hi = lo;
    for (size_t v = 0; v < sp.size() / 3; ++v) {
        const Vec3f q = skin_point(v);
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
    }
    const float size = distance(lo, hi);

    // Each curve's start (a uniform cubic B-spline's at u = 0: (P0 + 4 P1 + P2) / 6)
    // on the exported skin, in object space.
    std::vector<Vec3f> roots;
    size_t first = 0;
    float worst = 0;
    for (double c : counts) {
        auto at = [&](size_t k) {
            return Vec3f{float(P[3 * (first + k)]), float(P[3 * (first + k) + 1]),
                         float(P[3 * (first + k) + 2])};
        };
        const Vec3f root = (at(0) + at(1) * 4.0f + at(2)) / 6.0f;
        float d = INFINITY;
        for (size_t t = 0; t + 2 < si.size(); t += 3) {
            const Vec3f a = skin_point(size_t(si[t])), b = skin_point(size_t(si[t + 1])),
                        cc = skin_point(size_t(si[t + 2]));
            d = std::min(d, distance(root, closest_on_triangle(root, a, b, cc)));
        }
        worst = std::max(worst, d);
        roots.push_back(root);
        first += size_t(c);
    }
    EXPECT_LT(worst, 1e-5f * size);

    // The skin rendered bare: where a root is seen (its depth is the pixel's) inside a
    // cell (the 3x3 pixels around it show one cell), the curve names that cell and
    // has its colour: to 5 %, as a camera hit blends neighbouring cells' colours over
    // its footprint (the mosaic shader's antialiasing) and a root does not; the two
    // types differ thirty-fold.
    json bare = json::parse(slurp(scene_path));
    bare["objects"][0].erase("fur");
    bare["film"]["layers"] = {{"albedo", "float"}};
    const std::string bare_path = tmp.write("bare.json", bare.dump());
    ASSERT_EQ(run_pelage("render " + bare_path + " -q --res 320x240 --spp 4 -o " +
                             tmp.file("bare.exr"),
                         nullptr, &err),
              0)
        << err;
    const Exr img(tmp.file("bare.exr"));
    const int ca = img.channel("albedo.R"), cd = img.channel("depth.Z"),
              cc = img.channel("shader.cell_id");
    ASSERT_TRUE(ca >= 0 && cd >= 0 && cc >= 0);
    const renderer::CameraDesc cam = renderer::load_scene_file(bare_path).camera;
    const Vec3f w = normalize(cam.look_at - cam.position);
    const Vec3f u = normalize(cross(w, cam.up)), v = cross(u, w);
    const float tan_h = std::tan(0.5f * cam.fov_deg * float(M_PI) / 180);
    const float aspect = float(img.width) / float(img.height);
    size_t seen = 0, wrong_cell = 0, wrong_colour = 0;
    for (size_t s = 0; s < roots.size(); ++s) {
        const Vec3f p = M.apply(roots[s].x, roots[s].y, roots[s].z) - cam.position;
        const float z = dot(p, w);
        const float sx = dot(p, u) / z, sy = dot(p, v) / z;
        const int x =
            int(std::floor((sx + tan_h * aspect) / (2 * tan_h * aspect) * img.width));
        const int y = int(std::floor((tan_h - sy) / (2 * tan_h) * img.height));
        if (x < 1 || y < 1 || x + 1 >= img.width || y + 1 >= img.height) continue;
        if (std::abs(img.at(x, y, cd) - z) > 0.01f * z) continue;  // hidden
        bool one_cell = true;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                one_cell = one_cell && img.at(x + dx, y + dy, cc) == img.at(x, y, cc);
        if (!one_cell) continue;
        ++seen;
        wrong_cell += cell[s] != double(img.at(x, y, cc));
        for (int k = 0; k < 3; ++k)
            if (std::abs(colour[3 * s + size_t(k)] - img.at(x, y, ca + k)) >
                1e-3 + 0.05 * std::abs(colour[3 * s + size_t(k)])) {
                ++wrong_colour;
                break;
            }
    }
    EXPECT_GT(seen, 300u);
    EXPECT_LE(wrong_cell, seen / 100) << wrong_cell << " of " << seen;
    EXPECT_LE(wrong_colour, seen / 100) << wrong_colour << " of " << seen;
}

TEST(UsdExport, AnObjectTurntableBecomesTimeSamplesOfItsTransform) {
    REQUIRE_READERS();
    TempDir tmp;
    const std::string scene_path =
        fur_scene(tmp, R"({"animation": {"frames": 3, "first_frame": 1001, "fps": 25,
                 "turntable": {"degrees": 90, "target": "object", "objects": ["sphere"]}}})");
    const std::string usda = tmp.file("turn.usda");
    std::string err;
    ASSERT_EQ(
        run_pelage("export " + scene_path + " -q --no-fur -o " + usda, nullptr, &err), 0)
        << err;
    const json usd = read_usd(tmp, usda);
    EXPECT_EQ(usd["stage"]["startTimeCode"], json::array({1001}));
    EXPECT_EQ(usd["stage"]["endTimeCode"], json::array({1003}));
    EXPECT_EQ(usd["stage"]["timeCodesPerSecond"], json::array({25}));
    const json &xf = usd["prims"]["/coat/sphere"]["attrs"]["xformOp:transform"];
    ASSERT_TRUE(xf.contains("samples")) << xf.dump();
    const renderer::SceneDesc desc = renderer::load_scene_file(scene_path);
    for (int f = 0; f < 3; ++f) {
        const std::vector<double> m =
            xf["samples"].at(std::to_string(1001 + f)).get<std::vector<double>>();
        ASSERT_EQ(m.size(), 16u);
        const renderer::Affine &a =
            renderer::scene_at_frame(desc, f).objects[0].transform;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(m[4 * size_t(r) + size_t(c)], a.m[c][r], 1e-6);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[12 + size_t(c)], a.m[c][3], 1e-6);
    }
    // The skin itself does not change in its own space: one value, no samples.
    const json &skin = usd["prims"]["/coat/sphere/skin"]["attrs"];
    EXPECT_TRUE(skin["points"].contains("value"));
    EXPECT_FALSE(skin["points"].contains("samples"));
    EXPECT_FALSE(usd["prims"].contains("/coat/sphere/fur"));
}

TEST(UsdExport, AClipsFramesBecomeTimeSamplesOfThePosedSkin) {
    REQUIRE_READERS();
    TempDir tmp;
    const std::string mesh = tmp.write("tube.gltf", armature_tube(12, 8));
    const std::string cells = simulate_two_type_cells(tmp, mesh, 200);
    const json scene = {{"camera", {{"position", {0, 1, 5}}, {"look_at", {0, 0.75, 0}}}},
                        {"film", {{"width", 32}, {"height", 32}, {"spp", 1}}},
                        {"lights", {{{"type", "environment"}}}},
                        {"animation", {{"frames", 12}, {"fps", 24}}},
                        {"objects",
                         {{{"name", "tube"},
                           {"mesh", mesh},
                           {"cells", cells},
                           {"animation", {{"clip", "Sway"}}},
                           {"material", {{"shader", "clonal_mosaic"}}}}}}};
    const std::string scene_path = tmp.write("clip.json", scene.dump());
    const std::string usda = tmp.file("clip.usda");
    std::string err;
    ASSERT_EQ(run_pelage("export " + scene_path + " -q --frames 0,4,8 -o " + usda,
                         nullptr, &err),
              0)
        << err;
    const json usd = read_usd(tmp, usda);
    const json &points = usd["prims"]["/coat/tube/skin"]["attrs"]["points"];
    ASSERT_TRUE(points.contains("samples")) << "the posed skin is not time-sampled";
    // Each sample is the skin the renderer poses for that frame.
    const renderer::SceneDesc desc = renderer::load_scene_file(scene_path);
    const renderer::PluginRegistry plugins;
    double worst = 0, moved = 0;
    std::vector<double> first;
    for (int f : {0, 4, 8}) {
        const std::vector<double> p =
            points["samples"].at(std::to_string(f)).get<std::vector<double>>();
        const renderer::Scene posed(renderer::scene_at_frame(desc, f), plugins);
        const renderer::MeshData &m = *posed.geometry().objects()[0].mesh;
        ASSERT_EQ(p.size(), 3 * size_t(m.num_vertices));
        for (size_t k = 0; k < p.size(); ++k)
            worst = std::max(worst, std::abs(p[k] - m.object_positions[k]));
        if (first.empty()) first = p;
        for (size_t k = 0; k < p.size(); ++k)
            moved = std::max(moved, std::abs(p[k] - first[k]));
    }
    EXPECT_LT(worst, 1e-6);  // TinyUSDZ prints floats back to 8 digits
    EXPECT_GT(moved, 0.05) << "the clip's frames should move the spine";
}

TEST(UsdExport, TheSameBytesAtAnyThreadCount) {
    TempDir tmp;
    const std::string scene_path = fur_scene(tmp);
    for (const char *threads : {"1", "2"}) {
        fs::create_directories(tmp.path() / threads);
        std::string err;
        ASSERT_EQ(
            run_pelage("export " + scene_path + " -q --texture 128 --threads " + threads +
                           " -o " + (tmp.path() / threads / "c.usda").string(),
                       nullptr, &err),
            0)
            << err;
    }
    for (const char *file : {"c.usda", "c_sphere.png"}) {
        const std::string one = slurp((tmp.path() / "1" / file).string());
        EXPECT_FALSE(one.empty()) << file;
        EXPECT_TRUE(one == slurp((tmp.path() / "2" / file).string())) << file;
    }
}

TEST(UsdExport, BadRequestsFailWithTheFieldAndWriteNothing) {
    TempDir tmp;
    const std::string scene_path = fur_scene(tmp);
    const struct {
        std::string args, message;
    } cases[] = {
        {"-o " + tmp.file("coat.txt"), "OpenUSD text (.usda)"},
        {"-o " + tmp.file("no/such/coat.usda"), "does not exist"},
        {"--object ground -o " + tmp.file("c.usda"), "\"ground\" has no pattern"},
        {"--object nose -o " + tmp.file("c.usda"), "no object is named \"nose\""},
        {"--frames 1-3 -o " + tmp.file("c.usda"), "no animation"},
        {"--texture 32 --max-points 1000 -o " + tmp.file("c.usda"), "--max-points"},
        {"--texture 16 -o " + tmp.file("c.usda"), "raise --texture"},
    };
    for (const auto &c : cases) {
        std::string err;
        EXPECT_EQ(run_pelage("export " + scene_path + " -q " + c.args, nullptr, &err), 2)
            << c.args;
        EXPECT_NE(err.find(c.message), std::string::npos) << c.args << ": " << err;
    }
    // Only the scene and the cells grown for it.
    size_t files = 0;
    for (const auto &e : fs::directory_iterator(tmp.path())) files += e.is_regular_file();
    EXPECT_EQ(files, 2u);
}

}  // namespace
}  // namespace pelage::test
