// renderer/fur's groom: per cell type and per body region, every groomed key takes the
// value the rules give at its root (a type's factor or value, then each region's lerp by
// its weight, blended barycentrically between the triangle's corners), and density by
// region thins the roots to that density. The expected values are computed here from
// the rules as docs/guide/fur.md states them, not through strand_groom().
#include "renderer/fur/strand_groom.h"

#include <gtest/gtest.h>

#include <cmath>

#include "renderer/bsdf/hair_pigments.h"
#include "renderer/fur/fur_grow.h"

namespace pelage::renderer {
namespace {

// Eight unit right triangles in the y = 0 plane (normal +y); one region, "east": weight
// 1 on triangles 4–7, 0 on 0–2, and on triangle 3 0 / 1 / 0 at its corners (a blend).
struct GroomStrip {
    std::vector<float> positions, regions;
    std::vector<uint32_t> triangles;
    GroomStrip() {
        for (uint32_t k = 0; k < 8; ++k) {
            const float x0 = 3.0f * float(k);
            const float v[9] = {x0, 0, 0, x0 + 1, 0, 0, x0, 0, -1};
            positions.insert(positions.end(), v, v + 9);
            for (uint32_t c = 0; c < 3; ++c) triangles.push_back(3 * k + c);
            for (int c = 0; c < 3; ++c)
                regions.push_back(k >= 4 ? 1.0f : k == 3 && c == 1 ? 1.0f : 0.0f);
        }
    }
    SkinMesh mesh() const {
        SkinMesh m;
        m.positions = positions.data();
        m.triangles = triangles.data();
        m.num_vertices = 24;
        m.num_triangles = 8;
        m.region_corners = regions.data();
        m.num_regions = 1;
        return m;
    }
    static float weight(const SurfacePoint &r) {
        return r.triangle >= 4 ? 1.0f : r.triangle == 3 ? r.b1 : 0.0f;
    }
};

const PigmentLookup by_triangle = [](const SurfacePoint &s, Vec3f, Vec3f) {
    RootPigment r;
    r.colour = {0.6f, 0.5f, 0.4f};
    r.cell_type = int(s.triangle % 2);
    return r;
};

float lerp(float a, float b, float w) { return a + (b - a) * w; }

FurParams groomed_params() {
    using G = FurParams::Groomed;
    FurParams p;
    p.density = 3000;
    p.segments = 4;
    p.curve = FurParams::Curve::flat;
    p.length = 0.2f;
    p.length_variation = 0;
    p.comb_direction = {1, 0, 0};
    p.comb_jitter_deg = 0;
    p.melanin_jitter = 0;
    p.vary(G::length).by_type = {1, 2};  // factors
    p.vary(G::length).in = {{0, 0.5f}};
    p.comb_angle_deg = 30;
    p.vary(G::comb_angle).by_type = {20, 40};  // values
    p.vary(G::comb_angle).in = {{0, 70.0f}};
    p.vary(G::root_radius).by_type = {1, 3};
    p.vary(G::beta_m).in = {{0, 0.6f}};
    p.colour_in = {{0, Rgb{0.9f, 0.2f, 0.1f}}};
    return p;
}

TEST(StrandGroom, EveryKeyTakesItsTypesThenItsRegionsValue) {
    const GroomStrip strip;
    const FurParams p = groomed_params();
    const Strands s = grow_fur(p, strip.mesh(), by_triangle);
    ASSERT_GT(s.size(), 3000u);
    ASSERT_EQ(s.beta.size(), 2 * s.size());
    size_t blended = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        const SurfacePoint &r = s.roots[i];
        const float w = GroomStrip::weight(r);
        const int type = int(r.triangle % 2);
        blended += w > 0.05f && w < 0.95f;
        const float *P = &s.points[i * s.points_per_strand * 4];
        const Vec3f root{P[0], P[1], P[2]}, tip{P[16], P[17], P[18]};
        const Vec3f d = tip - root;
        const float L = std::sqrt(dot(d, d));
        // Length: the regions' lerp, then the type's factor.
        EXPECT_NEAR(L, lerp(0.2f, 0.5f, w) * (type ? 2.0f : 1.0f), 1e-4f) << i;
        // Comb angle: the type's value, then the region's.
        const float angle = std::asin(d.y / L) * 180 / 3.14159265f;
        EXPECT_NEAR(angle, lerp(type ? 40.0f : 20.0f, 70.0f, w), 0.05f) << i;
        EXPECT_FLOAT_EQ(P[3], 0.0015f * (type ? 3.0f : 1.0f));
        EXPECT_NEAR(s.beta[2 * i], lerp(0.25f, 0.6f, w), 1e-6f);
        EXPECT_FLOAT_EQ(s.beta[2 * i + 1], 0.3f);
        // Colour: σ_a moves from the skin's towards the region's, both matched in the
        // coat as deep as it grows at the root, over the skin's colour.
        const float weights[1] = {w};
        const float depth = fur_depth(strand_groom(p, weights, type));
        const Rgb under{0.6f, 0.5f, 0.4f};
        const Rgb skin = sigma_a_from_coat_colour(under, 0.3f, depth, under),
                  east = sigma_a_from_coat_colour({0.9f, 0.2f, 0.1f}, 0.3f, depth, under);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(s.sigma_a[i][k], lerp(skin[k], east[k], w),
                        1e-4f * std::max(1.0f, east[k]));
    }
    EXPECT_GT(blended, 100u);
}

TEST(StrandGroom, DensityByRegionThinsTheRootsToIt) {
    using G = FurParams::Groomed;
    const GroomStrip strip;
    FurParams p;
    p.density = 2000;
    p.segments = 2;
    p.vary(G::density).in = {{0, 8000.0f}};
    p.vary(G::density).by_type = {1, 0.5f};
    const Strands s = grow_fur(p, strip.mesh(), by_triangle);
    // Expected per triangle (area 1/2): density × type factor, the blend triangle 3
    // (type 1) at the mean of lerp(2000, 8000, b1) = 2000 + 6000/3.
    double expected[8], count[8] = {0};
    for (uint32_t t = 0; t < 8; ++t) {
        const double d = t >= 4 ? 8000 : t == 3 ? 4000 : 2000;
        expected[t] = 0.5 * d * (t % 2 ? 0.5 : 1.0);
    }
    for (const SurfacePoint &r : s.roots) count[r.triangle] += 1;
    for (int t = 0; t < 8; ++t)
        EXPECT_NEAR(count[t], expected[t], 4 * std::sqrt(expected[t])) << t;
    EXPECT_EQ(max_density(p), 8000.0);
}

TEST(StrandGroom, WithoutVaryingKeysStrandsKeepTheCoatsValues) {
    FurParams p;
    p.length = 0.3f;
    p.comb_angle_deg = 12;
    const StrandGroom g = strand_groom(p, nullptr, 1);
    EXPECT_EQ(g.length, 0.3f);
    EXPECT_EQ(g.comb_angle_deg, 12.0f);
    EXPECT_FALSE(beta_varies(p));
}

}  // namespace
}  // namespace pelage::renderer
