// Cryptomatte of a grown pattern, end to end: `pelage render` with film.cryptomatte,
// then `pelage matte` pulls mattes out of the file as a compositor would. Each sample on
// the sphere has exactly one cell type, so the type mattes partition the object's matte;
// a fully covered spot pixel is that type in the shader layer too.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::vector<float> read_channel(const std::string &path, const std::string &channel,
                                int *w = nullptr, int *h = nullptr) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> px(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    const int c = s.channelindex(channel);
    if (c < 0) return {};
    if (w) *w = s.width;
    if (h) *h = s.height;
    std::vector<float> out(size_t(s.width) * s.height);
    for (size_t i = 0; i < out.size(); ++i) out[i] = px[i * s.nchannels + c];
    return out;
}

TEST(CryptomatteCli, TypeMattesPartitionTheObjectAndAgreeWithTheShaderLayer) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 300);
    const std::string scene = tmp.write("s.json", R"({
      "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 45},
      "film": {"width": 48, "height": 48, "spp": 32, "cryptomatte": true,
               "compression": "piz"},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"name": "ball", "mesh": ")" + mesh +
                                                      R"(", "cells": ")" + cells +
                                                      R"(",
                   "material": {"shader": "clonal_mosaic"}}]
    })");
    const std::string exr = tmp.file("o.exr");
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + exr), 0);
    EXPECT_EQ(OIIO::ImageInput::open(exr)->spec().get_string_attribute("compression"),
              "piz");
    std::string out;
    ASSERT_EQ(run_pelage("matte " + exr + " --list", &out), 0);
    for (const char *want : {"CryptoObject", "CryptoType", "CryptoCell", "CryptoLineage",
                             "  F\n", "  B\n", "  ball\n", "ball/cell ", "ball/clone "})
        EXPECT_NE(out.find(want), std::string::npos) << want << "\n" << out;

    ASSERT_EQ(run_pelage("matte " + exr + " -q --name ball -o " + tmp.file("ball.exr")),
              0);
    ASSERT_EQ(
        run_pelage("matte " + exr + " -q --layer type --name F -o " + tmp.file("f.exr")),
        0);
    ASSERT_EQ(run_pelage("matte " + exr + " -q --layer CryptoType --name B -o " +
                         tmp.file("b.exr")),
              0);
    int w = 0, h = 0;
    const auto ball = read_channel(tmp.file("ball.exr"), "A", &w, &h);
    const auto f = read_channel(tmp.file("f.exr"), "A");
    const auto b = read_channel(tmp.file("b.exr"), "A");
    const auto alpha = read_channel(exr, "A");
    const auto type = read_channel(exr, "shader.cell_type");
    ASSERT_EQ(w, 48);
    ASSERT_EQ(f.size(), ball.size());
    int spots = 0, edges = 0;
    for (size_t i = 0; i < ball.size(); ++i) {
        EXPECT_NEAR(f[i] + b[i], ball[i], 1e-5) << i;
        EXPECT_NEAR(ball[i], alpha[i], 1e-3) << i;
        if (f[i] == 1.0f) {
            EXPECT_EQ(type[i], 0.0f) << i;  // F is type 0
            ++spots;
        }
        edges += f[i] > 0.05f && f[i] < 0.95f;
    }
    EXPECT_GT(spots, 20);
    EXPECT_GT(edges, 10);  // antialiased: spot edges take fractional coverage
    // Every cell belongs to one clone: the clones' mattes add up to the object's too
    // (a wildcard selects them all).
    ASSERT_EQ(
        run_pelage("matte " + exr + " -q --layer lineage --name 'ball/clone *' -o " +
                   tmp.file("clones.exr")),
        0);
    const auto clones = read_channel(tmp.file("clones.exr"), "A");
    double missing = 0;
    for (size_t i = 0; i < ball.size(); ++i) missing += ball[i] - clones[i];
    EXPECT_LT(missing / ball.size(), 0.01);  // only ids beyond the 6 ranks are dropped

    // Mistakes exit 2 naming what is wrong; nothing is written.
    std::string err;
    EXPECT_EQ(run_pelage("matte " + exr + " --layer fur --name x -o " + tmp.file("x.png"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("CryptoFur"), std::string::npos) << err;
    EXPECT_EQ(
        run_pelage("matte " + exr + " --layer type --name Q -o " + tmp.file("x.png"),
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("\"Q\""), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.png")));
    // A layer no material offers is refused at load.
    const std::string bad = tmp.write("bad.json", R"({
      "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
      "film": {"width": 8, "height": 8, "cryptomatte": ["object", "fur"]},
      "objects": [{"mesh": "procedural:icosphere:1"}]})");
    EXPECT_EQ(run_pelage("render " + bad + " -o " + tmp.file("x.exr"), nullptr, &err), 2);
    EXPECT_NE(err.find("film.cryptomatte[1]"), std::string::npos) << err;
}

// With fur over the skin, each strand carries its root's type: the type mattes still
// partition the object's (the camera sees mostly hair), so "the spots" selects the
// spots' hair too, and the object's matte is the image's alpha. Also with the strands
// (0.14 px wide here) widened to a pixel and kept by their opacity (min_pixel_width):
// a widened hit that is kept is a hit of its strand in every layer.
class FurMattes : public ::testing::TestWithParam<double> {};

TEST_P(FurMattes, StrandsAreInTheirRootsTypeMatteAndTheObjectsIsAlpha) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 300);
    const std::string scene =
        tmp.write("s.json", R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 42},
      "film": {"width": 40, "height": 40, "spp": 16, "cryptomatte": ["object", "type"]},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"name": "ball", "mesh": ")" +
                                mesh + R"(", "cells": ")" + cells +
                                R"(",
                   "material": {"shader": "clonal_mosaic"},
                   "fur": {"density": 3000, "length": 0.15, "root_radius": 0.004,
                           "tip_radius": 0.001, "seed": 3, "min_pixel_width": )" +
                                std::to_string(GetParam()) + "}}]}");
    const std::string exr = tmp.file("o.exr");
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + exr), 0);
    for (const char *name : {"ball", "F", "B"})
        ASSERT_EQ(
            run_pelage("matte " + exr + " -q --layer " + (name[1] ? "object" : "type") +
                       " --name " + name + " -o " + tmp.file(std::string(name) + ".exr")),
            0)
            << name;
    const auto ball = read_channel(tmp.file("ball.exr"), "A");
    const auto f = read_channel(tmp.file("F.exr"), "A");
    const auto b = read_channel(tmp.file("B.exr"), "A");
    const auto alpha = read_channel(exr, "A");
    ASSERT_EQ(alpha.size(), ball.size());
    double covered = 0, typed = 0, partial = 0;
    for (size_t i = 0; i < ball.size(); ++i) {
        EXPECT_NEAR(f[i] + b[i], ball[i], 1e-5) << i;
        EXPECT_NEAR(ball[i], alpha[i], 1e-5) << i;
        covered += ball[i];
        typed += f[i];
        partial += ball[i] > 0.01 && ball[i] < 0.99;
    }
    EXPECT_GT(covered, 200);  // the ball and its hair fill much of the frame
    EXPECT_GT(typed, 10);     // and some of it is the spots'
    EXPECT_GT(partial, 20);   // the hair beyond the outline covers pixels in part
}

INSTANTIATE_TEST_SUITE_P(CryptomatteCli, FurMattes, ::testing::Values(0.0, 1.0));

}  // namespace
}  // namespace pelage::test
