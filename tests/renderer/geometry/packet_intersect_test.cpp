// Camera-ray packets must find exactly the hits single rays find: the path loop treats
// a packet lane's RTCRayHit as if rtcIntersect1 had filled it.
#include "renderer/geometry/packet_intersect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "renderer/core/sampler.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

// An instanced mesh (used twice), a baked one and the ground: every kind of hit id.
constexpr const char *scene_json = R"({
  "camera": {"position": [0, 0, 6], "look_at": [0, 0, 0]},
  "lights": [{"type": "environment", "color": 1}],
  "objects": [{"mesh": "procedural:icosphere:2", "transform": {"translate": [-1.2, 0, 0]}},
              {"mesh": "procedural:icosphere:2", "transform": {"translate": [1.2, 0, 0]}},
              {"mesh": "procedural:icosphere:1", "transform": {"translate": [0, 1.5, -1]}},
              {"mesh": "procedural:plane:1x1",
               "transform": {"scale": 10, "translate": [0, -1, 0]}}]
})";

RTCRayHit trace_single(RTCScene scene, Vec3f o, Vec3f d) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh;
}

TEST(PacketIntersector, PacketsOfEverySizeFindTheHitsOfSingleRays) {
    TempDir tmp;
    const renderer::SceneDesc desc =
        renderer::load_scene_file(tmp.write("s.json", scene_json));
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    const RTCScene rtc = scene.geometry().scene();
    const renderer::PacketIntersector packets(scene.geometry().device(), rtc);
    EXPECT_TRUE(packets.width() == 1 || packets.width() == 4 || packets.width() == 8 ||
                packets.width() == 16);

    constexpr int K = renderer::PacketIntersector::max_rays;
    renderer::Sampler sampler(7, 0);
    int hits = 0, misses = 0, instanced = 0;
    for (int batch = 0; batch < 400; ++batch) {
        const int n = 1 + batch % K;  // every partial packet size, masked lanes
        Vec3f o[K], d[K];
        for (int i = 0; i < n; ++i) {
            sampler.start_pixel_sample(uint32_t(batch), uint32_t(i), 0);
            const auto [a, b] = sampler.get_2d();
            const auto [c, e] = sampler.get_2d();
            // Half the batches coherent (a camera's fan), half random directions.
            o[i] = batch % 2 ? Vec3f{4 * c - 2, 4 * e - 2, 6} : Vec3f{0, 0, 6};
            const Vec3f aim{6 * a - 3, 4 * b - 2, 0};
            d[i] = normalize(aim - o[i]);
        }
        RTCRayHit out[K];
        packets.intersect(o, d, n, out);
        for (int i = 0; i < n; ++i) {
            const RTCRayHit ref = trace_single(rtc, o[i], d[i]);
            ASSERT_EQ(out[i].hit.geomID, ref.hit.geomID) << batch << " " << i;
            EXPECT_EQ(out[i].ray.org_x, o[i].x);
            EXPECT_EQ(out[i].ray.dir_z, d[i].z);
            EXPECT_EQ(out[i].ray.tnear, 0.0f);
            if (ref.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
                EXPECT_TRUE(std::isinf(out[i].ray.tfar));
                ++misses;
                continue;
            }
            ++hits;
            instanced += ref.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
            EXPECT_EQ(out[i].hit.instID[0], ref.hit.instID[0]);
            EXPECT_EQ(out[i].hit.primID, ref.hit.primID);
            EXPECT_NEAR(out[i].ray.tfar, ref.ray.tfar, 1e-5f * ref.ray.tfar);
            EXPECT_NEAR(out[i].hit.u, ref.hit.u, 1e-4f);
            EXPECT_NEAR(out[i].hit.v, ref.hit.v, 1e-4f);
            const Vec3f ng{out[i].hit.Ng_x, out[i].hit.Ng_y, out[i].hit.Ng_z},
                ng_ref{ref.hit.Ng_x, ref.hit.Ng_y, ref.hit.Ng_z};
            EXPECT_GT(dot(ng, ng_ref), 0.9999f * length(ng) * length(ng_ref));
        }
    }
    // The rays reach everything: misses, baked and instanced hits.
    EXPECT_GT(misses, 100);
    EXPECT_GT(hits, 1000);
    EXPECT_GT(instanced, 100);
}

}  // namespace
}  // namespace pelage::test
