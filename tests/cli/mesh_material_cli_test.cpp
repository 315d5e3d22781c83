// The mesh_material plugin end to end: an OBJ whose .mtl gives one quad a colour (Kd)
// and another a colour and a texture (map_Kd) is rendered, and the image's albedo layer
// must show exactly the .mtl's numbers (Kd, Kd × texel), and the plugin's default where
// the file gives no material.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// Three unit-height quads in the xy-plane, seen face on: x in [-3, -1] has no material,
// [-1, 1] is "red", [1, 3] is "skin" (with the texture tex/skin.exr).
void write_zoo(const TempDir &tmp) {
    std::filesystem::create_directories(tmp.path() / "tex");
    const float texel[3] = {0.5f, 0.25f, 1.0f};
    std::vector<float> pixels;
    for (int i = 0; i < 16; ++i) pixels.insert(pixels.end(), texel, texel + 3);
    auto out = OIIO::ImageOutput::create(tmp.file("tex/skin.exr"));
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(tmp.file("tex/skin.exr"),
                          OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
    tmp.write("zoo.mtl",
              "newmtl red\nKd 0.8 0.1 0.05\n"
              "newmtl skin\nKd 0.5 1 0.8\nmap_Kd tex/skin.exr\n");
    tmp.write("zoo.obj",
              "mtllib zoo.mtl\n"
              "v -3 -1 0\nv -1 -1 0\nv -1 1 0\nv -3 1 0\n"
              "v 1 -1 0\nv 1 1 0\nv 3 -1 0\nv 3 1 0\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "f 1/1 2/2 3/3 4/4\n"
              "usemtl red\nf 2/1 5/2 6/3 3/4\n"
              "usemtl skin\nf 5/1 7/2 8/3 6/4\n");
}

// The albedo layer's RGB at the centre of each quad (left, middle, right).
std::vector<std::array<float, 3>> albedo_at_quads(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> px(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    const int r = s.channelindex("albedo.R");
    if (r < 0) return {};
    std::vector<std::array<float, 3>> out;
    for (int x : {10, 30, 50}) {
        const float *p = &px[(size_t(s.height / 2) * s.width + x) * s.nchannels];
        out.push_back({p[r], p[r + 1], p[r + 2]});
    }
    return out;
}

std::string scene_with(const std::string &params) {
    return R"({
      "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 12},
      "film": {"width": 60, "height": 20, "spp": 1, "filter": {"type": "box"},
               "layers": {"albedo": "float"}},
      "lights": [{"type": "environment"}],
      "objects": [{"mesh": "zoo.obj",
                   "material": {"shader": "mesh_material", "params": )" +
           params + "}}]}";
}

void expect_rgb(const std::array<float, 3> &got, const std::array<float, 3> &want) {
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(got[c], want[c]) << "channel " << c;
}

TEST(MeshMaterialCli, AlbedoIsTheMtlColourTimesItsTexture) {
    TempDir tmp;
    write_zoo(tmp);
    std::string err;
    const std::string scene =
        tmp.write("s.json", scene_with(R"({"default": [0.2, 0.3, 0.4]})"));
    ASSERT_EQ(
        run_pelage("render " + scene + " -q -o " + tmp.file("a.exr"), nullptr, &err), 0)
        << err;
    const auto a = albedo_at_quads(tmp.file("a.exr"));
    ASSERT_EQ(a.size(), 3u);
    expect_rgb(a[0], {0.2f, 0.3f, 0.4f});
    expect_rgb(a[1], {0.8f, 0.1f, 0.05f});
    expect_rgb(a[2], {0.5f * 0.5f, 1.0f * 0.25f, 0.8f * 1.0f});

    const std::string plain = tmp.write("p.json", scene_with(R"({"textures": 0})"));
    ASSERT_EQ(
        run_pelage("render " + plain + " -q -o " + tmp.file("p.exr"), nullptr, &err), 0)
        << err;
    const auto p = albedo_at_quads(tmp.file("p.exr"));
    ASSERT_EQ(p.size(), 3u);
    expect_rgb(p[0], {0.5f, 0.5f, 0.5f});
    expect_rgb(p[2], {0.5f, 1.0f, 0.8f});
}

TEST(MeshMaterialCli, AMissingTextureOrNoMaterialsIsExit2NamingThem) {
    TempDir tmp;
    write_zoo(tmp);
    std::filesystem::remove(tmp.path() / "tex/skin.exr");
    std::string err;
    const std::string scene = tmp.write("s.json", scene_with("{}"));
    EXPECT_EQ(run_pelage("render " + scene + " -o " + tmp.file("a.exr"), nullptr, &err),
              2);
    EXPECT_NE(err.find("objects[0].material"), std::string::npos) << err;
    EXPECT_NE(err.find("material \"skin\": no such image " + tmp.file("tex/skin.exr")),
              std::string::npos)
        << err;

    std::filesystem::remove(tmp.path() / "zoo.mtl");
    EXPECT_EQ(run_pelage("render " + scene + " -o " + tmp.file("a.exr"), nullptr, &err),
              2);
    EXPECT_NE(err.find("defines no materials"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
