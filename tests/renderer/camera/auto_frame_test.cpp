// Automatic framing against the renderer's own projection (Camera::world_to_ndc, the
// matrix the EXR header records): every point inside the frame less its margin, one
// on that border, at any scale and for any up axis.
#include "renderer/camera/auto_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "renderer/camera/camera.h"

namespace pelage::renderer {
namespace {

// A quadruped-like cloud: a long body and four legs, `scale` units long, along `along`
// with `up` up.
std::vector<Vec3f> animal_points(float scale, Vec3f along, Vec3f up, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    const Vec3f side = cross(up, along);
    std::vector<Vec3f> pts;
    for (int i = 0; i < 3000; ++i) {  // body: an ellipsoid-ish box above the legs
        pts.push_back((along * (0.5f * u(rng)) + side * (0.12f * u(rng)) +
                       up * (0.35f + 0.12f * u(rng))) *
                      scale);
    }
    for (int leg = 0; leg < 4; ++leg)
        for (int i = 0; i < 200; ++i)
            pts.push_back((along * ((leg < 2 ? 0.35f : -0.35f) + 0.03f * u(rng)) +
                           side * ((leg % 2 ? 0.08f : -0.08f) + 0.03f * u(rng)) +
                           up * (0.12f + 0.12f * u(rng))) *
                          scale);
    return pts;
}

// Largest |NDC − ½|·2 over the points: 1 is the image border.
float extent_in_frame(const std::vector<Vec3f> &pts, const CameraDesc &cam, int w,
                      int h) {
    const auto m = Camera(cam, w, h).world_to_ndc();
    float most = 0;
    for (const Vec3f &p : pts) {
        const float x = p.x * m[0] + p.y * m[4] + p.z * m[8] + m[12];
        const float y = p.x * m[1] + p.y * m[5] + p.z * m[9] + m[13];
        const float ww = p.x * m[3] + p.y * m[7] + p.z * m[11] + m[15];
        EXPECT_GT(ww, 0) << "a point behind the camera";
        most = std::max({most, std::abs(2 * x / ww - 1), std::abs(2 * y / ww - 1)});
    }
    return most;
}

TEST(AutoFrame, EveryPointInsideTheMarginAndTheFrameTight) {
    for (const float scale : {0.002f, 1.0f, 150.0f})
        for (const Vec3f up : {Vec3f{0, 1, 0}, Vec3f{0, 0, 1}, Vec3f{-1, 0, 0}}) {
            const Vec3f along = std::abs(up.x) > 0 ? Vec3f{0, 0, 1} : Vec3f{1, 0, 0};
            const auto pts = animal_points(scale, along, up, 7);
            FramingRequest rq;
            rq.up = up;
            rq.aspect = 16.0f / 9.0f;
            const Framing f = frame_points(pts, rq);
            const float e = extent_in_frame(pts, f.camera, 1600, 900);
            EXPECT_LE(e, 1 - rq.margin + 1e-3f) << "scale " << scale;
            EXPECT_GE(e, 1 - rq.margin - 0.01f) << "not tight at scale " << scale;
            // The camera looks down on the animal from above its lowest point.
            EXPECT_GT(dot(f.camera.position, up), f.ground);
            EXPECT_NEAR(f.ground, 0.0f, 0.01f * scale);
            // The long axis is found whatever the orientation.
            EXPECT_GT(std::abs(dot(f.long_axis, along)), 0.99f);
        }
}

TEST(AutoFrame, ScalesWithTheObject) {
    const auto small = animal_points(1, {1, 0, 0}, {0, 1, 0}, 3);
    std::vector<Vec3f> big;
    for (const Vec3f &p : small) big.push_back(p * 100.0f);
    const Framing a = frame_points(small, {}), b = frame_points(big, {});
    EXPECT_NEAR(length(b.camera.position - a.camera.position * 100.0f), 0.0f,
                1e-3f * length(b.camera.position));
    EXPECT_NEAR(b.radius, 100 * a.radius, 1e-3f * b.radius);
}

TEST(AutoFrame, RefusesWhatCannotBeFramed) {
    EXPECT_THROW(frame_points({}, {}), std::invalid_argument);
    FramingRequest no_up;
    no_up.up = {0, 0, 0};
    EXPECT_THROW(frame_points({{0, 0, 0}}, no_up), std::invalid_argument);
    EXPECT_THROW(frame_points({{0, 0, 0}, {NAN, 0, 0}}, {}), std::invalid_argument);
    // A single point is framed at a finite distance.
    const Framing one = frame_points({{1, 2, 3}}, {});
    EXPECT_TRUE(std::isfinite(one.camera.position.x));
}

}  // namespace
}  // namespace pelage::renderer
