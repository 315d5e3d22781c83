// Cryptomatte against its specification's own data and a scene of known coverage: names
// hash as Psyop's sample manifest lists them, and a matte rebuilt from the written file
// (manifest → id → ranked coverage) matches the area each object covers in each pixel.
// Also the honest AOVs around it: background ids and depth, camera matrices.
#include "renderer/image/cryptomatte.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <tuple>

#include "renderer/image/image_layers.h"
#include "renderer/image/image_output.h"
#include "renderer/integrator/render.h"
#include "renderer/scene/scene.h"
#include "sim/core/input_error.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

TEST(Cryptomatte, MurmurHash3MatchesTheReferenceVectors) {
    // MurmurHash3_x86_32, seed 0 (Appleby's SMHasher verification values).
    EXPECT_EQ(murmur3_32(""), 0u);
    EXPECT_EQ(murmur3_32("hello"), 0x248bfa47u);
    EXPECT_EQ(murmur3_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
    EXPECT_EQ(murmur3_32("", 1), 0x514e28b7u);
}

TEST(Cryptomatte, NamesHashAsThePsyopSampleManifestListsThem) {
    // sample_images/sidecar_manifest/bunny_CryptoObject_manifest.json of Psyop's
    // Cryptomatte repository.
    EXPECT_EQ(cryptomatte_hash("bunny"), 0x13851a76u);
    EXPECT_EQ(cryptomatte_hash("bush"), 0xf763d090u);
    // Every id is a normal, finite float: the exponent is never 0 or 255.
    for (int i = 0; i < 20000; ++i) {
        const float id = cryptomatte_id(cryptomatte_hash("cell " + std::to_string(i)));
        ASSERT_TRUE(std::isnormal(id)) << i;
    }
    EXPECT_EQ(cryptomatte_layer_name("type"), "CryptoType");
    EXPECT_EQ(cryptomatte_key("CryptoObject").size(), 7u);
}

TEST(Cryptomatte, RanksAreHeaviestFirstAndTiesAreOrderedByKey) {
    CryptomatteFilm film(1, 1, 1, 4);
    film.add(0, 0, 0, 7, 1.0f);
    film.add(0, 0, 0, 3, 2.0f);
    film.add(0, 0, 0, 9, 2.0f);
    film.add(0, 0, 0, 7, 0.5f);
    const auto r = film.ranked(0, 0, 0);
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r[0].key, 3u);
    EXPECT_EQ(r[1].key, 9u);
    EXPECT_EQ(r[2].key, 7u);
    EXPECT_FLOAT_EQ(r[2].weight, 1.5f);
    // A fifth id finds the four slots taken and is not counted.
    film.add(0, 0, 0, 1, 1.0f);
    film.add(0, 0, 0, 2, 1.0f);
    EXPECT_EQ(film.ranked(0, 0, 0).size(), 4u);
}

// Looking straight down at y = 0 from height 10 with a 90° vertical field of view and a
// 40 × 20 image: one pixel is one unit, raster x is world x + 20 and raster y is world
// z + 10. "left" covers x < -9.75 and "right" x > -9.75 in the top half (z < 0), so
// pixel column 10 is a quarter left and three quarters right; the bottom half is sky.
// (procedural:plane:1x1 spans [-1, 1]².)
constexpr int W = 40, H = 20;
const char *two_quads = R"({
  "camera": {"position": [0, 10, 0], "look_at": [0, 0, 0], "up": [0, 0, -1],
             "fov": 90},
  "film": {"width": 40, "height": 20, "spp": 64, "filter": {"type": "box"},
           "cryptomatte": ["object"], "cryptomatte_ranks": 3},
  "lights": [{"type": "environment", "color": 1}],
  "objects": [
    {"name": "left", "mesh": "procedural:plane:1x1",
     "transform": {"scale": [5.125, 1, 5], "translate": [-14.875, 0, -5]},
     "material": {"shader": "diffuse"}},
    {"name": "right", "mesh": "procedural:plane:1x1",
     "transform": {"scale": [14.875, 1, 5], "translate": [5.125, 0, -5]},
     "material": {"shader": "diffuse"}}]
})";

struct ReadBack {
    OIIO::ImageSpec spec;
    std::vector<float> px;
    float at(int x, int y, const std::string &channel) const {
        const int c = spec.channelindex(channel);
        EXPECT_GE(c, 0) << channel;
        return c < 0 ? 0.0f : px[(size_t(y) * spec.width + x) * spec.nchannels + c];
    }
};

ReadBack render_to_exr(const TempDir &tmp, const std::string &json) {
    const SceneDesc desc = load_scene_file(tmp.write("scene.json", json));
    const PluginRegistry plugins;
    const Scene scene(desc, plugins);
    const RenderResult r = render(scene, RenderOptions{});
    std::vector<CryptomatteSource> sources;
    for (size_t l = 0; l < scene.matte_layers().size(); ++l)
        sources.push_back({scene.matte_layers()[l], [&scene, l](uint64_t key) {
                               return scene.matte_name(int(l), key);
                           }});
    const ImageLayers layers = image_layers(*r.film, desc.film, scene.shader_aov_names(),
                                            sources, [](const std::string &) {});
    ImageMetadata meta;
    const Camera camera(desc.camera, desc.film.width, desc.film.height);
    meta.world_to_camera = camera.world_to_camera();
    meta.world_to_ndc = camera.world_to_ndc();
    meta.compression = desc.film.compression;
    const std::string path = tmp.file("out.exr");
    write_exr(path, layers, meta);
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << OIIO::geterror();
    ReadBack b;
    b.spec = in->spec();
    b.px.resize(size_t(b.spec.width) * b.spec.height * b.spec.nchannels);
    EXPECT_TRUE(
        in->read_image(0, 0, 0, b.spec.nchannels, OIIO::TypeDesc::FLOAT, b.px.data()));
    return b;
}

// A compositor's matte of `name`: the manifest gives its id; every rank whose id
// matches adds its coverage (the specification's decoding, written from it here).
std::vector<float> matte(const ReadBack &b, const std::string &layer,
                         const std::string &name) {
    std::string manifest;
    for (const auto &a : b.spec.extra_attribs) {
        const std::string n = a.name().string();
        if (n.rfind("cryptomatte/", 0) == 0 && n.size() > 5 &&
            n.substr(n.size() - 5) == "/name" && a.get_string() == layer) {
            const std::string prefix = n.substr(0, n.size() - 4);
            manifest = b.spec.get_string_attribute(prefix + "manifest");
            EXPECT_EQ(b.spec.get_string_attribute(prefix + "hash"), "MurmurHash3_32");
            EXPECT_EQ(b.spec.get_string_attribute(prefix + "conversion"),
                      "uint32_to_float32");
        }
    }
    const auto j = nlohmann::json::parse(manifest);
    EXPECT_TRUE(j.contains(name)) << manifest;
    const uint32_t bits = uint32_t(std::stoul(j.value(name, "0"), nullptr, 16));
    float id;
    std::memcpy(&id, &bits, 4);
    std::vector<float> m(size_t(b.spec.width) * b.spec.height, 0.0f);
    for (int rank = 0;; ++rank) {
        const std::string image = layer + (rank / 2 < 10 ? "0" : "") +
                                  std::to_string(rank / 2),
                          idc = image + (rank % 2 ? ".B" : ".R"),
                          cov = image + (rank % 2 ? ".A" : ".G");
        if (b.spec.channelindex(idc) < 0) break;
        for (int y = 0; y < b.spec.height; ++y)
            for (int x = 0; x < b.spec.width; ++x)
                if (b.at(x, y, idc) == id)
                    m[size_t(y) * b.spec.width + x] += b.at(x, y, cov);
    }
    return m;
}

TEST(Cryptomatte, MatteRebuiltFromTheFileMatchesTheKnownCoverage) {
    TempDir tmp;
    const ReadBack b = render_to_exr(tmp, two_quads);
    ASSERT_EQ(b.spec.width, W);
    // Three ranks: two RGBA images, the second half used.
    for (const char *c : {"CryptoObject00.R", "CryptoObject00.A", "CryptoObject01.B"})
        EXPECT_GE(b.spec.channelindex(c), 0) << c;
    EXPECT_LT(b.spec.channelindex("CryptoObject02.R"), 0);
    const std::vector<float> left = matte(b, "CryptoObject", "left"),
                             right = matte(b, "CryptoObject", "right");
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            // Box filter: coverage is the pixel's area fraction.
            const double want_left = y >= 10 ? 0 : x < 10 ? 1 : x == 10 ? 0.25 : 0;
            const double want_right = y >= 10 ? 0 : 1 - want_left;
            const size_t p = size_t(y) * W + x;
            // 64 stratified samples: ±1/64 at the edge column.
            EXPECT_NEAR(left[p], want_left, 0.02) << x << "," << y;
            EXPECT_NEAR(right[p], want_right, 0.02) << x << "," << y;
            // The mattes add up to the beauty's alpha (the same samples).
            EXPECT_NEAR(left[p] + right[p], b.at(x, y, "A"), 1e-3);
        }
    // The edge pixel ranks "right" (0.75) before "left" (0.25).
    EXPECT_GT(b.at(10, 5, "CryptoObject00.G"), b.at(10, 5, "CryptoObject00.A"));
}

TEST(Cryptomatte, CheckedByOiiotoolWithTheExpectedChannelNames) {
    TempDir tmp;
    render_to_exr(tmp, two_quads);
    const std::string cmd = "oiiotool --info -v " + tmp.file("out.exr") + " 2>&1";
    FILE *p = popen(cmd.c_str(), "r");
    ASSERT_TRUE(p);
    std::string out;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    ASSERT_EQ(pclose(p), 0) << out;
    for (const char *want :
         {"CryptoObject00.R (float)", "CryptoObject01.A (float)", "\"CryptoObject\"",
          "MurmurHash3_32", "uint32_to_float32", "worldToCamera", "worldToNDC"})
        EXPECT_NE(out.find(want), std::string::npos) << want << "\n" << out;
}

TEST(HonestAovs, BackgroundHasNoIdInfiniteDepthAndNoUnnamedShaderSlots) {
    TempDir tmp;
    const ReadBack b = render_to_exr(tmp, two_quads);
    // Sky: no object, no primitive, infinitely far.
    EXPECT_EQ(b.at(3, 15, "id.object"), -1.0f);
    EXPECT_EQ(b.at(3, 15, "id.primitive"), -1.0f);
    EXPECT_EQ(b.at(3, 15, "depth.Z"), std::numeric_limits<float>::infinity());
    EXPECT_EQ(b.at(3, 5, "id.object"), 0.0f);
    EXPECT_NEAR(b.at(3, 5, "depth.Z"), 10.0f, 1e-4);
    // The diffuse plugin names no AOV slot: no shader.* channel is written.
    for (const auto &n : b.spec.channelnames) EXPECT_NE(n.rfind("shader.", 0), 0u) << n;
}

TEST(HonestAovs, CameraMatricesProjectAPixelsPointBackOntoIt) {
    TempDir tmp;
    const ReadBack b = render_to_exr(tmp, two_quads);
    float cam[16], ndc[16];
    ASSERT_TRUE(b.spec.getattribute("worldtocamera", OIIO::TypeMatrix, cam));
    ASSERT_TRUE(b.spec.getattribute("worldtoNDC", OIIO::TypeMatrix, ndc));
    // Pixel (5, 5)'s centre sees the ground at (-14.5, 0, -4.5) (the scene's layout).
    const float p[4] = {-14.5f, 0, -4.5f, 1};
    float c[4] = {0, 0, 0, 0}, n[4] = {0, 0, 0, 0};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            c[j] += p[i] * cam[i * 4 + j];  // Imath: row vector times matrix
            n[j] += p[i] * ndc[i * 4 + j];
        }
    // Camera space: x right, y up, looking down -z at depth 10.
    EXPECT_NEAR(c[0], -14.5f, 1e-4);
    EXPECT_NEAR(c[1], 4.5f, 1e-4);
    EXPECT_NEAR(c[2], -10.0f, 1e-4);
    // NDC from the bottom-left corner: (5.5 / 40, 1 - 5.5 / 20), z = 1 / depth.
    EXPECT_NEAR(n[0] / n[3], 5.5f / W, 1e-5);
    EXPECT_NEAR(n[1] / n[3], 1 - 5.5f / H, 1e-5);
    EXPECT_NEAR(n[2] / n[3], 0.1f, 1e-5);
}

TEST(HonestAovs, LayersAreWrittenAsAskedWithTheChosenCompression) {
    TempDir tmp;
    std::string json = two_quads;
    const std::string film = R"("cryptomatte": ["object"], "cryptomatte_ranks": 3},)";
    json.replace(json.find(film), film.size(),
                 R"("cryptomatte": ["object"], "cryptomatte_ranks": 3,
                    "layers": {"albedo": false, "depth": "half", "N": "float"},
                    "compression": "piz"},)");
    const ReadBack b = render_to_exr(tmp, json);
    EXPECT_LT(b.spec.channelindex("albedo.R"), 0);
    const auto format = [&](const char *c) {
        return b.spec.channelformat(b.spec.channelindex(c));
    };
    EXPECT_EQ(format("depth.Z"), OIIO::TypeDesc::HALF);
    EXPECT_EQ(format("N.X"), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(format("R"), OIIO::TypeDesc::HALF);
    EXPECT_EQ(format("id.object"), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(format("CryptoObject00.R"), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(b.spec.get_string_attribute("compression"), "piz");
    // Ids in half would not be exact: refused, naming the field.
    std::string bad = two_quads;
    bad.replace(bad.find(film), film.size(), R"("layers": {"id": "half"}},)");
    try {
        load_scene_file(tmp.write("bad.json", bad));
        ADD_FAILURE() << "accepted";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("film.layers.id"), std::string::npos)
            << e.what();
    }
}

TEST(HonestAovs, FrameRateIsOpenExrsRational) {
    TempDir tmp;
    for (const auto &[fps, num, den] :
         {std::tuple{24.0, 24, 1}, std::tuple{29.97, 29970, 1000}}) {
        ImageLayers l;
        l.width = l.height = 2;
        l.names = {"R", "G", "B", "A"};
        l.half = {1, 1, 1, 1};
        l.pixels.assign(16, 0.5f);
        ImageMetadata meta;
        meta.fps = fps;
        const std::string path = tmp.file("f.exr");
        write_exr(path, l, meta);
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in);
        int r[2] = {0, 0};
        ASSERT_TRUE(in->spec().getattribute("FramesPerSecond", OIIO::TypeRational, r));
        EXPECT_EQ(r[0], num);
        EXPECT_EQ(r[1], den);
    }
}

}  // namespace
}  // namespace pelage::test
