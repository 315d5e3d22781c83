// The coat stays on the skin through a clip, as a compositor sees it: a surface point's
// Cryptomatte clone (lineage) id is the same at frame 0 and at frame 24 of the bending
// strip, wherever the pose has carried the point in the picture. The point is found by
// tracing frame 0's pixel into frame 0's scene, then carried to frame 24 on the posed
// triangle (same triangle, same barycentric point) and projected by frame 24's camera.
#include <OpenImageIO/imageio.h>
#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "renderer/camera/camera.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_frame/scene_frame.h"
#include "tests/renderer/animation/skinned_strip.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

// One EXR channel as floats, row-major.
std::vector<float> channel(const std::string &exr, const std::string &name, int *w,
                           int *h) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    const int c = s.channelindex(name);
    if (c < 0) return {};
    *w = s.width;
    *h = s.height;
    std::vector<float> px(size_t(s.width) * s.height);
    in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, px.data());
    return px;
}

// The first hit of the camera ray through raster point (x, y).
RTCRayHit trace(const Scene &scene, const Camera &camera, float x, float y) {
    const CameraRay r = camera.generate(x, y, 0.5f, 0.5f);
    RTCRayHit rh{};
    rh.ray.org_x = r.o.x, rh.ray.org_y = r.o.y, rh.ray.org_z = r.o.z;
    rh.ray.dir_x = r.d.x, rh.ray.dir_y = r.d.y, rh.ray.dir_z = r.d.z;
    rh.ray.tfar = 1e30f;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(scene.geometry().scene(), &ctx, &rh);
    return rh;
}

TEST(ClipMatteCli, ASurfacePointKeepsItsCloneFromFrameToFrame) {
    TempDir tmp;
    const std::string mesh = tmp.write("strip.gltf", skinned_strip());
    std::string err;
    ASSERT_EQ(run_pelage("look " + mesh +
                             " --clip bend --frames 0-24x24 --res 320x180 --spp 4 "
                             "--cryptomatte -q -o " +
                             tmp.file("strip.exr"),
                         nullptr, &err),
              0)
        << err;
    int w = 0, h = 0;
    const std::string id = "CryptoLineage00.R", cover = "CryptoLineage00.G";
    const std::vector<float> id0 = channel(tmp.file("strip.0000.exr"), id, &w, &h),
                             cov0 = channel(tmp.file("strip.0000.exr"), cover, &w, &h),
                             id24 = channel(tmp.file("strip.0024.exr"), id, &w, &h),
                             cov24 = channel(tmp.file("strip.0024.exr"), cover, &w, &h);
    ASSERT_FALSE(id0.empty() || id24.empty() || cov0.empty() || cov24.empty())
        << "no " << id << " layer";
    // A pixel inside one clone: its own and its 8 neighbours' top id the same, and
    // nearly all of its coverage.
    auto inside = [&](const std::vector<float> &ids, const std::vector<float> &cov, int x,
                      int y) {
        if (x < 1 || y < 1 || x + 1 >= w || y + 1 >= h) return false;
        const float v = ids[size_t(y) * w + x];
        if (v == 0 || cov[size_t(y) * w + x] < 0.9f) return false;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (ids[size_t(y + dy) * w + x + dx] != v) return false;
        return true;
    };

    const SceneDesc desc = load_scene_file(tmp.file("strip.json"));
    const PluginRegistry plugins;
    const SceneDesc d0 = scene_at_frame(desc, 0), d24 = scene_at_frame(desc, 24);
    const Scene s0(d0, plugins), s24(d24, plugins);
    const Camera cam0(d0.camera, w, h);
    const Camera cam24(d24.camera, w, h);
    const std::array<float, 16> ndc24 = cam24.world_to_ndc();
    const MeshData &posed = *s24.geometry().objects()[0].mesh;
    ASSERT_TRUE(s24.geometry().objects()[0].baked);

    int compared = 0, same = 0, same_pixel = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!inside(id0, cov0, x, y)) continue;
            const RTCRayHit rh = trace(s0, cam0, float(x) + 0.5f, float(y) + 0.5f);
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ||
                s0.geometry().object_of(rh.hit.geomID, rh.hit.instID[0]) != 0)
                continue;
            // The same (triangle, barycentric) point on frame 24's pose.
            const uint32_t *tri = &posed.triangles[3 * size_t(rh.hit.primID)];
            const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
            const Vec3f p = posed.position_at(tri[0], 0) * b0 +
                            posed.position_at(tri[1], 0) * b1 +
                            posed.position_at(tri[2], 0) * b2;
            // Imath row vectors: (p, 1) · M, then divided by w; NDC y runs up.
            float q[4];
            for (int c = 0; c < 4; ++c)
                q[c] = p.x * ndc24[0 * 4 + c] + p.y * ndc24[1 * 4 + c] +
                       p.z * ndc24[2 * 4 + c] + ndc24[3 * 4 + c];
            const int x24 = int(std::floor(q[0] / q[3] * float(w)));
            const int y24 = int(std::floor((1 - q[1] / q[3]) * float(h)));
            if (!inside(id24, cov24, x24, y24)) continue;
            // Seen at frame 24: the tip folds back over the strip, hiding some points.
            const RTCRayHit seen =
                trace(s24, cam24, float(x24) + 0.5f, float(y24) + 0.5f);
            if (seen.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
            const Vec3f o{seen.ray.org_x, seen.ray.org_y, seen.ray.org_z},
                d{seen.ray.dir_x, seen.ray.dir_y, seen.ray.dir_z};
            if (length(o + d * seen.ray.tfar - p) > 0.05f) continue;
            ++compared;
            const float v = id0[size_t(y) * w + x];
            same += id24[size_t(y24) * w + x24] == v;
            same_pixel += inside(id24, cov24, x, y) && id24[size_t(y) * w + x] == v;
        }
    ASSERT_GE(compared, 150) << "too few pixels inside clones in both frames";
    std::printf("%d of %d points keep their clone; %d pixels keep it in place\n", same,
                compared, same_pixel);
    // A point next to a clone's edge can round to a pixel across it: a few.
    EXPECT_GE(double(same), 0.97 * compared) << same << " of " << compared;
    // The pose moves the points in the picture: a pattern fixed in the image (or in
    // space) would not keep them.
    EXPECT_LT(double(same_pixel), 0.8 * compared) << same_pixel << " of " << compared;
}

// A clip's frames share what does not change between them (the pattern and its
// closest-cell index): each frame of one run is, byte for byte, the frame rendered by a
// run of its own, the skin and the fur coloured by the pattern under its roots.
TEST(ClipFramesCli, AFrameOfARunIsTheFrameRenderedAlone) {
    TempDir tmp;
    const std::string mesh = tmp.write("strip.gltf", skinned_strip());
    std::string err;
    ASSERT_EQ(run_pelage("look " + mesh +
                             " --clip bend --frames 0-24x12 --res 160x90 --spp 2 --fur "
                             "-q -o " +
                             tmp.file("strip.exr"),
                         nullptr, &err),
              0)
        << err;
    for (const char *frame : {"12", "24"}) {
        ASSERT_EQ(run_pelage("render " + tmp.file("strip.json") + " --frames " + frame +
                                 " -q -o " + tmp.file("alone.####.exr"),
                             nullptr, &err),
                  0)
            << err;
        const std::string n = std::string(frame).size() == 2 ? "00" : "000";
        std::ifstream a(tmp.file("strip." + n + frame + ".exr"), std::ios::binary),
            b(tmp.file("alone." + n + frame + ".exr"), std::ios::binary);
        const std::string run((std::istreambuf_iterator<char>(a)), {}),
            alone((std::istreambuf_iterator<char>(b)), {});
        ASSERT_FALSE(run.empty());
        EXPECT_TRUE(run == alone)
            << "frame " << frame << " differs from its render alone";
    }
}

// A frame token in `look -o` names the frames as `render -o` takes it: the frames are
// numbered in its place and its style, and the pattern, the scene and the previews are
// named after the text before it (not "fox.####.cells").
TEST(ClipFramesCli, LookHonoursTheFrameTokenOfItsOutput) {
    TempDir tmp;
    const std::string mesh = tmp.write("strip.gltf", skinned_strip());
    std::string err;
    for (const std::string &name : {std::string("a.####.exr"), std::string("b.%03d.exr")})
        ASSERT_EQ(run_pelage("look " + mesh + " --clip bend --frames 0-1 --res 32x18 " +
                                 "--spp 1 -q -o " + tmp.file(name),
                             nullptr, &err),
                  0)
            << name << ": " << err;
    for (const char *f : {"a.0000.exr", "a.0001.exr", "a.cells", "a.json",
                          "a_preview.0000.png", "a_preview.0001.png", "b.000.exr",
                          "b.001.exr", "b.cells", "b.json", "b_preview.000.png"})
        EXPECT_TRUE(std::ifstream(tmp.file(f)).good()) << f << " missing";
    for (const char *f : {"a.####.0000.exr", "a.####.cells", "a.####.json",
                          "b.%03d.0000.exr", "b.%03d.cells"})
        EXPECT_FALSE(std::ifstream(tmp.file(f)).good()) << f << " written";
}

}  // namespace
}  // namespace pelage::test
