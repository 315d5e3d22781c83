// renderer/fur/clump_guides: the guide a strand clumps to is the nearest within two clump
// radii (the lowest index among equally near ones), checked against a brute-force search
// over every guide.
#include "renderer/fur/clump_guides.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "renderer/fur/root_sampling.h"

namespace pelage::renderer {
namespace {

TEST(ClumpGuides, NearestGuideIsTheBruteForceNearest) {
    // A folded sheet: two 4 × 4 squares meeting at a right angle, so guides lie in
    // cells of all three axes and some grid cells hold guides of both faces.
    const std::vector<float> positions = {0, 0, 0, 4, 0, 0, 4, 0, 4,
                                          0, 0, 4, 0, 4, 0, 0, 4, 4};
    const std::vector<uint32_t> triangles = {0, 2, 1, 0, 3, 2, 0, 4, 5, 0, 5, 3};
    SkinMesh mesh;
    mesh.positions = positions.data();
    mesh.triangles = triangles.data();
    mesh.num_vertices = 6;
    mesh.num_triangles = 4;
    FurParams params;
    params.clump = 0.5f;
    params.clump_radius = 0.04f;
    const RootSampler sampler(mesh);
    const ClumpGuides guides(params, mesh, sampler);
    ASSERT_GT(guides.size(), 5000u);

    const float reach = 2 * params.clump_radius;
    uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(state >> 40) * 0x1p-24f;
    };
    int found = 0, none = 0;
    for (int q = 0; q < 4000; ++q) {
        // Points on and just off the sheet, some beyond its edges.
        const Vec3f p{next() * 4.4f - 0.2f, next() * 0.3f - 0.1f, next() * 4.4f - 0.2f};
        int64_t best = -1;
        float best_d2 = reach * reach;
        for (size_t g = 0; g < guides.size(); ++g) {
            const Vec3f e = guides.root(g) - p;
            const float d2 = e.x * e.x + e.y * e.y + e.z * e.z;
            if (d2 < best_d2 || (d2 == best_d2 && int64_t(g) < best))
                best_d2 = d2, best = g;
        }
        ASSERT_EQ(guides.nearest(p), best) << "at " << p.x << " " << p.y << " " << p.z;
        (best >= 0 ? found : none)++;
    }
    // Both outcomes are exercised.
    EXPECT_GT(found, 1000);
    EXPECT_GT(none, 100);
}

}  // namespace
}  // namespace pelage::renderer
