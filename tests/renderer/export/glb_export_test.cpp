// pelage bake --glb checked by readers independent of pelage and assimp: the Khronos
// glTF validator (npm; tests/export/validate_gltf.mjs) and OpenImageIO decoding the PNG
// inside, compared with the baked EXR.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool validator_installed() {
    return fs::is_regular_file(fs::path(PELAGE_NODE_MODULES) /
                               "gltf-validator/index.js") &&
           std::system("node --version >/dev/null 2>&1") == 0;
}

std::vector<float> read_image(const std::string &path, int *w, int *h, int *c) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    *w = in->spec().width, *h = in->spec().height, *c = in->spec().nchannels;
    std::vector<float> px(size_t(*w) * *h * *c);
    in->read_image(0, 0, 0, *c, OIIO::TypeDesc::FLOAT, px.data());
    return px;
}

// The sRGB encoding (IEC 61966-2-1), written here from the standard.
int srgb_byte(float linear) {
    const double c = std::min(1.0, std::max(0.0, double(linear)));
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    return int(std::lround(e * 255));
}

// A GLB container (glTF 2.0 specification, 4.4): its JSON and its binary chunk.
struct Glb {
    json doc;
    std::string bin;
    explicit Glb(const std::string &bytes) {
        auto u32 = [&](size_t at) {
            uint32_t v;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 28 || u32(0) != 0x46546C67 || u32(4) != 2) return;
        const uint32_t json_length = u32(12);
        doc = json::parse(bytes.substr(20, json_length), nullptr, false);
        const size_t bin_at = 20 + json_length;
        bin = bytes.substr(bin_at + 8, u32(bin_at));
    }
    // The bytes of buffer view `v`.
    std::string view(size_t v) const {
        const json &bv = doc["bufferViews"][v];
        return bin.substr(bv.value("byteOffset", size_t(0)), bv["byteLength"]);
    }
    std::vector<float> floats(size_t accessor) const {
        const json &a = doc["accessors"][accessor];
        const std::string b = view(a["bufferView"]);
        std::vector<float> v(b.size() / 4);
        std::memcpy(v.data(), b.data(), v.size() * 4);
        return v;
    }
    std::vector<uint32_t> uints(size_t accessor) const {
        const json &a = doc["accessors"][accessor];
        const std::string b = view(a["bufferView"]);
        std::vector<uint32_t> v(b.size() / 4);
        std::memcpy(v.data(), b.data(), v.size() * 4);
        return v;
    }
};

TEST(GlbExport, TheValidatorAcceptsItAndItsTextureIsTheBake) {
    if (!validator_installed())
        GTEST_SKIP() << "the npm readers are not installed in " PELAGE_NODE_MODULES
                        " (./quickstart.sh test installs them)";
    TempDir tmp;
    const std::string mesh = "procedural:sphere:24x16";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 300);
    std::string err;
    ASSERT_EQ(run_pelage("bake " + cells + " --mesh " + mesh + " --res 256 -q -o " +
                             tmp.file("p.exr") + " --glb " + tmp.file("p.glb"),
                         nullptr, &err),
              0)
        << err;
    const std::string report = tmp.file("report.json");
    const std::string cmd = "node " + source_path("tests/export/validate_gltf.mjs") +
                            " " + PELAGE_NODE_MODULES + " " + tmp.file("p.glb") + " " +
                            report + " 2>" + tmp.file("validator.err");
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(tmp.file("validator.err"));
    const json r = json::parse(slurp(report));
    EXPECT_EQ(r["issues"]["numErrors"], 0);
    EXPECT_EQ(r["issues"]["numWarnings"], 0) << r["issues"].dump();
    const sim::TriangleMesh sphere = sim::load_mesh(mesh);
    EXPECT_EQ(r["info"]["totalTriangleCount"], sphere.num_triangles());
    EXPECT_TRUE(r["info"]["hasTextures"].get<bool>());

    // The image inside, decoded by OpenImageIO, is the bake encoded as sRGB, texel for
    // texel.
    const Glb glb(slurp(tmp.file("p.glb")));
    ASSERT_TRUE(glb.doc.is_object());
    EXPECT_EQ(glb.doc["images"][0]["mimeType"], "image/png");
    tmp.write("inside.png", glb.view(glb.doc["images"][0]["bufferView"]));
    int pw, ph, pc, ew, eh, ec;
    const std::vector<float> png = read_image(tmp.file("inside.png"), &pw, &ph, &pc);
    const std::vector<float> exr = read_image(tmp.file("p.exr"), &ew, &eh, &ec);
    ASSERT_EQ(pw, ew);
    ASSERT_EQ(ph, eh);
    ASSERT_GE(pc, 3);
    int worst = 0;
    for (size_t p = 0; p < size_t(pw) * ph; ++p)
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(int(std::lround(png[p * pc + k] * 255)) -
                                             srgb_byte(exr[p * ec + k])));
    EXPECT_LE(worst, 1);

    // Each triangle's vertices are the mesh's, in its order, and its centroid's UV (v
    // down from the image's top row, glTF 2.0 §3.7.2.1) falls inside the bake's charts.
    const json &prim = glb.doc["meshes"][0]["primitives"][0];
    const std::vector<float> P = glb.floats(prim["attributes"]["POSITION"]),
                             UV = glb.floats(prim["attributes"]["TEXCOORD_0"]),
                             N = glb.floats(prim["attributes"]["NORMAL"]);
    const std::vector<uint32_t> idx = glb.uints(prim["indices"]);
    ASSERT_EQ(idx.size(), 3 * sphere.num_triangles());
    double worst_position = 0, worst_normal = 0;
    size_t outside = 0;
    for (size_t t = 0; t < sphere.num_triangles(); ++t) {
        double u = 0, v = 0;
        for (int c = 0; c < 3; ++c) {
            const uint32_t i = idx[3 * t + size_t(c)];
            const sim::Vec3d q = sphere.vertex(sim::TriId(t), c);
            for (int a = 0; a < 3; ++a)
                worst_position = std::max(worst_position, std::abs(P[3 * i + a] - q[a]));
            worst_normal = std::max(
                worst_normal, std::abs(1.0 - std::sqrt(N[3 * i] * N[3 * i] +
                                                       N[3 * i + 1] * N[3 * i + 1] +
                                                       N[3 * i + 2] * N[3 * i + 2])));
            u += UV[2 * i] / 3.0, v += UV[2 * i + 1] / 3.0;
        }
        const int x = std::min(ew - 1, int(u * ew)), y = std::min(eh - 1, int(v * eh));
        outside += exr[(size_t(y) * ew + x) * ec + 3] < 1;  // alpha: inside a chart
    }
    EXPECT_LT(worst_position, 1e-6);
    EXPECT_LT(worst_normal, 1e-5);
    EXPECT_EQ(outside, 0u);
}

TEST(GlbExport, BadRequestsFailWithTheFieldAndWriteNothing) {
    TempDir tmp;
    const std::string mesh = "procedural:sphere:12x8";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 100);
    std::string err;
    EXPECT_EQ(run_pelage("bake " + cells + " --mesh " + mesh + " --res 64 -q -o " +
                             tmp.file("p.exr") + " --glb " + tmp.file("p.gltf"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("--glb"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp.file("p.exr")));
    EXPECT_FALSE(fs::exists(tmp.file("p.gltf")));
}

}  // namespace
}  // namespace pelage::test
