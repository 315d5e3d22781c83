// Object motion blur (animation.shutter) against analytic averages over the shutter: a
// black plate sliding, and a black bar spinning, in front of a white sky. A pixel shows
// 1 − the fraction of the shutter and of its area (box filter) the object covers, with
// no shading noise (the plate reflects nothing, the sky is seen directly).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "renderer/geometry/fur_geometry.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_frame/scene_frame.h"
#include "sim/core/input_error.h"
#include "tests/renderer/animation/moving_plate.h"
#include "tests/renderer/animation/skinned_strip.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::renderer {
namespace {

using test::RenderedImage;

constexpr double pi = 3.14159265358979;

// Frame `frame` of the scene `json`, as `pelage render --frames` renders it.
RenderedImage render_frame(const std::string &json, const test::TempDir &dir, int frame) {
    const std::string path = dir.write("scene.json", json);
    const SceneDesc fd = scene_at_frame(load_scene_file(path), frame);
    const PluginRegistry plugins;
    const Scene scene(fd, plugins);
    RenderOptions o;
    const RenderResult r = render(scene, o);
    return {fd.film.width, fd.film.height, r.film->resolve(), r.stats};
}

// A camera 10 units up +z looking at the origin, its image 8 × 2 units of the z = 0
// plane: 64 × 16 pixels of 1/8 unit, (x, y) = (−4 + (col + ½)/8, 1 − (row + ½)/8).
std::string scene(const std::string &mesh, const std::string &clip,
                  const std::string &shutter, int steps, int spp, double albedo = 0) {
    const double fov = 2 * std::atan(0.1) * 180 / pi;
    return R"({"camera": {"position": [0, 0, 10], "look_at": [0, 0, 0], "fov": )" +
           std::to_string(fov) + R"(},
      "film": {"width": 64, "height": 16, "spp": )" +
           std::to_string(spp) + R"(, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 1}],
      "animation": {"frames": 4, "fps": 1, "shutter": )" +
           shutter + R"(, "motion_steps": )" + std::to_string(steps) + R"(},
      "objects": [{"mesh": ")" +
           mesh + R"(", "animation": {"clip": ")" + clip + R"(", "loop": false},
        "material": {"shader": "diffuse", "params": {"albedo": )" +
           std::to_string(albedo) + "}}}]}";
}

// Pixel (col, row)'s centre on the plane.
double px_x(double col) { return -4 + (col + 0.5) / 8; }
double px_y(double row) { return 1 - (row + 0.5) / 8; }

TEST(MotionBlur, ASlidingPlateCoversEachPixelForItsShareOfTheShutter) {
    test::TempDir tmp;
    tmp.write("plate.gltf", test::sliding_plate());
    // Frame 0 of a 1-fps animation: the shutter [0, 1] spans the whole clip, the plate's
    // x extent [−1 + 2t, 1 + 2t].
    const RenderedImage blurred =
        render_frame(scene(tmp.file("plate.gltf"), "slide", "[0, 1]", 2, 256), tmp, 0);
    // Point x is covered for t ∈ [(x − 1) / 2, (x + 1) / 2] ∩ [0, 1]; a pixel averages
    // that over its width (the box filter), here by the midpoint rule.
    auto coverage = [](int col) {
        double sum = 0;
        const int n = 1000;
        for (int k = 0; k < n; ++k) {
            const double x = -4 + (col + (k + 0.5) / n) / 8;
            sum += std::max(0.0, std::min(1.0, (x + 1) / 2) - std::max(0.0, (x - 1) / 2));
        }
        return sum / n;
    };
    double worst = 0;
    int ramp = 0;
    for (int col = 0; col < 64; ++col) {
        double mean = 0;
        for (int row = 0; row < 16; ++row) mean += blurred.at(col, row, 0);
        mean /= 16;
        const double expected = 1 - coverage(col);
        worst = std::max(worst, std::abs(mean - expected));
        ramp += expected > 0.05 && expected < 0.95;
        EXPECT_NEAR(mean, expected, 0.02)
            << "column " << col << " (x " << px_x(col) << ")";
    }
    EXPECT_GE(ramp, 26);  // the blur spans the plate's whole path, x in [−1, 3]
    // The same frame with the shutter closed is the plate at t = 0, sharp.
    const RenderedImage sharp =
        render_frame(scene(tmp.file("plate.gltf"), "slide", "[0, 0]", 2, 16), tmp, 0);
    for (int col = 0; col < 64; ++col) {
        const double x = px_x(col);
        const float v = sharp.at(col, 8, 0);
        if (std::abs(std::abs(x) - 1) > 0.1) EXPECT_EQ(v, std::abs(x) < 1 ? 0.0f : 1.0f);
    }
}

TEST(MotionBlur, ASpinningBarDarkensItsArcByItsAngularWidthOverTheSweep) {
    test::TempDir tmp;
    tmp.write("bar.gltf", test::spinning_bar());
    // The bar turns 90° about the origin during the shutter. The image's upper half-row
    // band y ∈ [0, 1] sees the first 90° of the sweep where r sin θ < 1: a point at
    // radius r and angle θ well inside the sweep is under the bar while |θ − φ| ≤
    // asin(0.1 / r), a 2 asin(0.1 / r) / (π / 2) share of the shutter. 17 motion steps
    // (5.6° apart) follow the arc to within 0.1 % of the radius.
    const RenderedImage im =
        render_frame(scene(tmp.file("bar.gltf"), "spin", "[0, 1]", 17, 256), tmp, 0);
    double sum = 0, expected = 0;
    int n = 0;
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 64; ++col) {
            const double x = px_x(col), y = px_y(row), r = std::hypot(x, y);
            const double theta = std::atan2(y, x);
            if (r < 1.2 || r > 2.8) continue;
            const double half = std::asin(0.1 / r) + 0.09 / r;  // + half a pixel's angle
            if (theta < half || theta > pi / 2 - half) continue;
            sum += 1 - im.at(col, row, 0);
            expected += 2 * std::asin(0.1 / r) / (pi / 2);
            ++n;
        }
    ASSERT_GE(n, 40);
    EXPECT_NEAR(sum / n, expected / n, 0.05 * expected / n) << n << " pixels";
    // Two steps would move the bar's points along chords: mid-shutter, its point at
    // radius 2 is at 1.41 and sweeps past the arc faster, which this test tells apart.
    const RenderedImage chord =
        render_frame(scene(tmp.file("bar.gltf"), "spin", "[0, 1]", 2, 256), tmp, 0);
    double chord_sum = 0;
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 64; ++col) {
            const double x = px_x(col), y = px_y(row), r = std::hypot(x, y);
            const double theta = std::atan2(y, x);
            const double half = std::asin(0.1 / r) + 0.09 / r;
            if (r < 1.2 || r > 2.8 || theta < half || theta > pi / 2 - half) continue;
            chord_sum += 1 - chord.at(col, row, 0);
        }
    EXPECT_GT(std::abs(chord_sum - expected), 0.1 * expected);
}

TEST(MotionBlur, WhatDoesNotMoveIsBitIdenticalWithAnOpenShutter) {
    test::TempDir tmp;
    tmp.write("plate.gltf", test::sliding_plate());
    // A clip held past its end poses nothing that moves (frame 3 of a 1-fps scene is 3 s
    // into a 1-s clip that does not loop): a grey plate lit by the sky, whose shading
    // samples would change if the open shutter drew a time.
    const std::string open =
        scene(tmp.file("plate.gltf"), "slide", "[0, 0.5]", 3, 16, 0.5);
    const std::string closed =
        scene(tmp.file("plate.gltf"), "slide", "[0, 0]", 2, 16, 0.5);
    const RenderedImage a = render_frame(open, tmp, 3), b = render_frame(closed, tmp, 3);
    EXPECT_EQ(a.pixels, b.pixels);
    // An object without a clip.
    auto sphere = [](const std::string &shutter) {
        return R"({"camera": {"position": [0, 0, 4]}, "film": {"width": 32, "height": 24},
          "lights": [{"type": "distant", "direction": [1, -1, -1], "color": 2}],
          "animation": {"frames": 2, "shutter": )" +
               shutter + R"(}, "objects": [{"mesh": "procedural:sphere:16x8"}]})";
    };
    EXPECT_EQ(render_frame(sphere("[0, 1]"), tmp, 1).pixels,
              render_frame(sphere("[0, 0]"), tmp, 1).pixels);
}

TEST(MotionBlur, TheShuttersLastStepIsTheNextFramesFirstSkinAndFur) {
    test::TempDir tmp;
    tmp.write("strip.gltf", test::skinned_strip());
    // The bending strip with fur, the shutter the whole frame: its closing pose is the
    // next frame's opening one, mesh and strands, to the bit (the hair of a frame does
    // not depend on which frames were rendered before it).
    auto desc = [&](const std::string &shutter) {
        return load_scene_file(
            tmp.write("s" + std::to_string(shutter.size()) + ".json",
                      R"({"camera": {"position": [2, 0, 8], "look_at": [2, 0, 0]},
              "animation": {"frames": 48, "fps": 24, "shutter": )" +
                          shutter + R"(, "motion_steps": 3},
              "objects": [{"mesh": "strip.gltf", "animation": {"clip": "bend"},
                "fur": {"density": 400, "length": 0.2, "seed": 3}}]})"));
    };
    const PluginRegistry plugins;
    const Scene blurred(scene_at_frame(desc("[0, 1]"), 10), plugins);
    const Scene next(scene_at_frame(desc("[0,0]"), 11), plugins);
    ASSERT_TRUE(blurred.moves());
    EXPECT_FALSE(next.moves());
    const MeshData &a = *blurred.geometry().objects()[0].mesh;
    const MeshData &b = *next.geometry().objects()[0].mesh;
    ASSERT_EQ(a.later_positions.size(), 2u);
    EXPECT_EQ(a.later_positions.back(), b.positions);
    EXPECT_NE(a.positions, b.positions);  // it moved during the shutter
    ASSERT_TRUE(blurred.fur() && next.fur());
    const FurLayer &fa = blurred.fur()->layers()[0], &fb = next.fur()->layers()[0];
    ASSERT_GT(fb.strands.size(), 20u);
    ASSERT_EQ(fa.later_points.size(), 2u);
    EXPECT_EQ(fa.later_points.back(), fb.strands.points);
    EXPECT_EQ(fa.strands.sigma_a, fb.strands.sigma_a);  // the same strands
    EXPECT_NE(fa.strands.points, fb.strands.points);
}

TEST(MotionBlur, ShutterErrorsNameTheField) {
    auto error = [](const std::string &animation) -> std::string {
        try {
            parse_scene(R"({"camera": {}, "animation": )" + animation +
                            R"(, "objects": [{"mesh": "procedural:sphere:8x4"}]})",
                        "s.json");
        } catch (const InputError &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(error(R"({"shutter": [0, 0.5], "motion_steps": 5})"), "");
    EXPECT_NE(error(R"({"shutter": [0.5, 0.2]})").find("animation.shutter[1]"),
              std::string::npos);
    EXPECT_NE(error(R"({"motion_steps": 1})").find("animation.motion_steps"),
              std::string::npos);
    EXPECT_NE(error(R"({"motion_steps": 200})").find("animation.motion_steps"),
              std::string::npos);
    const std::string twice =
        error(R"({"turntable": {"shutter": [0, 0.5]}, "shutter": [0, 0.5]})");
    EXPECT_NE(twice.find("given twice"), std::string::npos) << twice;
    const std::string object =
        error(R"({"turntable": {"target": "object"}, "shutter": [0, 0.5]})");
    EXPECT_NE(object.find("object turntable"), std::string::npos) << object;
}

}  // namespace
}  // namespace pelage::renderer
