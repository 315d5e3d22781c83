// renderer/fur: roots are area-uniform, counts follow density × area (per cell type),
// strands are identical at any thread count, each strand's colour is the skin's at its
// root, and strand shapes honour length, comb angle, radii and the skin.
#include "renderer/fur/fur_grow.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "renderer/bsdf/hair_pigments.h"
#include "renderer/fur/strand_groom.h"

namespace pelage::renderer {
namespace {

// Eight separate triangles in the y = 0 plane (normal +y) with areas k/2, k = 1..8.
struct Strip {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    std::vector<double> areas;
    Strip() {
        for (uint32_t k = 1; k <= 8; ++k) {
            const float x0 = 10.0f * k;
            const float v[9] = {x0, 0, 0, x0 + float(k), 0, 0, x0, 0, -1};
            positions.insert(positions.end(), v, v + 9);
            for (uint32_t c = 0; c < 3; ++c) triangles.push_back(3 * (k - 1) + c);
            areas.push_back(0.5 * k);
        }
    }
    SkinMesh mesh() const {
        SkinMesh m;
        m.positions = positions.data();
        m.triangles = triangles.data();
        m.num_vertices = uint32_t(positions.size() / 3);
        m.num_triangles = uint32_t(triangles.size() / 3);
        return m;
    }
    double area() const {
        double a = 0;
        for (double x : areas) a += x;
        return a;
    }
};

const PigmentLookup no_pigment = [](const SurfacePoint &, Vec3f, Vec3f) {
    return RootPigment{};
};

TEST(FurGrow, RootsAreAreaUniform) {
    const Strip strip;
    FurParams p;
    p.density = 2000;
    p.segments = 2;
    const Strands s = grow_fur(p, strip.mesh(), no_pigment);
    std::vector<double> count(8, 0);
    size_t near_corner0 = 0, on_largest = 0;
    for (const SurfacePoint &r : s.roots) {
        count[r.triangle] += 1;
        if (r.triangle == 7) {
            ++on_largest;
            near_corner0 += r.b1 + r.b2 < 0.5f;  // the sub-triangle b0 > ½: ¼ of the area
        }
    }
    // Chi-square of per-triangle counts against area / total, 7 degrees of freedom:
    // 24.3 is the 99.9 % quantile.
    double chi2 = 0;
    for (int t = 0; t < 8; ++t) {
        const double e = double(s.size()) * strip.areas[size_t(t)] / strip.area();
        chi2 += (count[size_t(t)] - e) * (count[size_t(t)] - e) / e;
    }
    EXPECT_LT(chi2, 24.3);
    // Within a triangle: a quarter of the roots in the quarter-area corner (4 σ).
    const double f = double(near_corner0) / double(on_largest);
    EXPECT_NEAR(f, 0.25, 4 * std::sqrt(0.25 * 0.75 / double(on_largest)));
}

TEST(FurGrow, CountFollowsDensityTimesAreaPerCellType) {
    const Strip strip;
    FurParams p;
    p.density = 3000;
    p.segments = 2;
    const Strands all = grow_fur(p, strip.mesh(), no_pigment);
    // Without thinning the count is density × area, rounded (its mean is exact).
    EXPECT_NEAR(double(all.size()), p.density * strip.area(), 1.0);

    // Odd triangles are cell type 1 at a quarter of the density of type 0.
    p.vary(FurParams::Groomed::density).by_type = {1.0f, 0.25f};
    const PigmentLookup typed = [](const SurfacePoint &s, Vec3f, Vec3f) {
        RootPigment r;
        r.cell_type = int(s.triangle % 2);
        return r;
    };
    const Strands thinned = grow_fur(p, strip.mesh(), typed);
    double a0 = 0, a1 = 0;
    for (size_t t = 0; t < 8; ++t) (t % 2 ? a1 : a0) += strip.areas[t];
    size_t n1 = 0;
    for (const SurfacePoint &r : thinned.roots) n1 += r.triangle % 2;
    const double e0 = p.density * a0, e1 = 0.25 * p.density * a1;
    EXPECT_NEAR(double(thinned.size() - n1), e0, 4 * std::sqrt(e0));
    EXPECT_NEAR(double(n1), e1, 4 * std::sqrt(e1));
}

TEST(FurGrow, SameStrandsAtOneAndTwoThreads) {
    const Strip strip;
    FurParams p;
    p.density = 4000;
    p.gravity = 0.5f;
    p.curl_radius = 0.1f;
    p.curl_turns = 2;
    p.clump = 0.5f;
    p.clump_radius = 0.2f;
    p.melanin_jitter = 0.3f;
    const PigmentLookup lookup = [](const SurfacePoint &s, Vec3f q, Vec3f) {
        RootPigment r;
        r.colour = {0.1f + 0.01f * q.x, s.b1 + 0.05f, 0.5f};
        r.cell_type = int(s.triangle % 2);
        return r;
    };
    Strands one, two;
    tbb::task_arena(1).execute([&] { one = grow_fur(p, strip.mesh(), lookup); });
    tbb::task_arena(2).execute([&] { two = grow_fur(p, strip.mesh(), lookup); });
    ASSERT_GT(one.size(), 10000u);
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.sigma_a, two.sigma_a);
    // Another seed gives other strands.
    p.seed = 2;
    const Strands other = grow_fur(p, strip.mesh(), lookup);
    EXPECT_NE(other.points, one.points);
}

// d'Eon et al. 2011's absorption per unit concentration (written here from the paper's
// RGB values, not taken from renderer/bsdf).
Rgb melanin_sigma_a(float eu, float pheo) {
    return {eu * 0.419f + pheo * 0.187f, eu * 0.697f + pheo * 0.4f,
            eu * 1.37f + pheo * 1.05f};
}

// The inverse hair_pigments.h gives for the coat `p` grows (its depth) over a skin of
// `skin` (measured against path-traced slabs in tests/cli/fur_colour_cli_test.cpp);
// here what matters is that each strand gets it.
Rgb colour_sigma_a(Rgb c, float bn, Rgb skin, const FurParams &p) {
    return sigma_a_from_coat_colour(c, bn, fur_depth(coat_groom(p)), skin);
}

void expect_near(Rgb a, Rgb b, float rel) {
    for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(a[k], b[k], rel * std::max(std::abs(b[k]), 1e-6f)) << k;
}

TEST(FurGrow, ByDefaultAStrandHasTheColourTheSkinShowsAtItsRoot) {
    const Strip strip;
    FurParams p;
    p.density = 500;
    p.melanin_jitter = 0;
    p.beta_n = 0.35f;
    const PigmentLookup lookup = [](const SurfacePoint &s, Vec3f, Vec3f) {
        RootPigment r;
        r.colour = {0.9f * s.b1 + 0.05f, 0.3f, 0.02f + 0.01f * float(s.triangle)};
        r.eumelanin = 5;  // ignored: the colour decides
        r.cell_type = int(s.triangle % 3);
        return r;
    };
    const Strands s = grow_fur(p, strip.mesh(), lookup);
    ASSERT_GT(s.size(), 1000u);
    for (size_t i = 0; i < s.size(); ++i)
        expect_near(s.sigma_a[i],
                    colour_sigma_a(lookup(s.roots[i], {}, {}).colour, 0.35f,
                                   lookup(s.roots[i], {}, {}).colour, p),
                    1e-4f);

    // Per type: type 0 a colour, type 1 melanins; type 2 (not listed) the coat's, here
    // the skin's melanins; then type 2 the absorption itself.
    using Kind = FurParams::Pigment::Kind;
    p.pigment.kind = Kind::skin_melanin;
    p.pigment_by_type.resize(2);
    p.pigment_by_type[0].kind = Kind::colour;
    p.pigment_by_type[0].colour = {0.8f, 0.7f, 0.5f};
    p.pigment_by_type[1].kind = Kind::melanin;
    p.pigment_by_type[1].eumelanin = 0.5f;
    p.pigment_by_type[1].pheomelanin = 2;
    for (const bool absorption : {false, true}) {
        if (absorption) {
            p.pigment_by_type.resize(3);
            p.pigment_by_type[2].kind = Kind::absorption;
            p.pigment_by_type[2].sigma_a = {0.25f, 1.5f, 4};
        }
        const Strands t = grow_fur(p, strip.mesh(), lookup);
        size_t seen[3] = {0, 0, 0};
        for (size_t i = 0; i < t.size(); ++i) {
            const int type = int(t.roots[i].triangle % 3);
            ++seen[type];
            const Rgb skin = lookup(t.roots[i], {}, {}).colour;
            expect_near(t.sigma_a[i],
                        type == 0    ? colour_sigma_a({0.8f, 0.7f, 0.5f}, 0.35f, skin, p)
                        : type == 1  ? melanin_sigma_a(0.5f, 2)
                        : absorption ? Rgb{0.25f, 1.5f, 4}
                                     : melanin_sigma_a(5, 0),
                        1e-5f);
        }
        for (size_t n : seen) EXPECT_GT(n, 100u);
    }

    // A black skin gives the darkest fibre the inversion reaches, not an infinite σ_a.
    p.pigment = {};
    p.pigment_by_type.clear();
    const Strands black =
        grow_fur(p, strip.mesh(), [](const SurfacePoint &, Vec3f, Vec3f) {
            RootPigment r;
            r.colour = {0, -1, std::nanf("")};
            return r;
        });
    for (const Rgb &a : black.sigma_a)
        expect_near(a, colour_sigma_a({1e-3f, 1e-3f, 1e-3f}, 0.35f, {0, 0, 0}, p), 1e-4f);
}

TEST(FurGrow, SkinMelaninIsScaledAndJittered) {
    const Strip strip;
    FurParams p;
    p.density = 500;
    p.melanin_jitter = 0;
    p.melanin_scale = 2;
    p.pigment.kind = FurParams::Pigment::Kind::skin_melanin;
    const PigmentLookup lookup = [](const SurfacePoint &s, Vec3f, Vec3f) {
        RootPigment r;
        r.eumelanin = 1.0f + float(s.triangle) + s.b1;
        r.pheomelanin = s.b2;
        return r;
    };
    const Strands s = grow_fur(p, strip.mesh(), lookup);
    ASSERT_GT(s.size(), 1000u);
    for (size_t i = 0; i < s.size(); ++i) {
        const RootPigment r = lookup(s.roots[i], {}, {});
        expect_near(s.sigma_a[i], melanin_sigma_a(2 * r.eumelanin, 2 * r.pheomelanin),
                    1e-5f);
    }
    // Jitter: within ±j of the skin's value, and not all at it.
    p.melanin_jitter = 0.2f;
    const Strands j = grow_fur(p, strip.mesh(), lookup);
    size_t moved = 0;
    for (size_t i = 0; i < j.size(); ++i) {
        const RootPigment r = lookup(j.roots[i], {}, {});
        const float skin = melanin_sigma_a(2 * r.eumelanin, 2 * r.pheomelanin).x;
        EXPECT_LE(std::abs(j.sigma_a[i].x - skin), 0.2f * skin * 1.0001f);
        moved += std::abs(j.sigma_a[i].x - skin) > 0.01f * skin;
    }
    EXPECT_GT(moved, j.size() / 2);
    // The block's own melanin replaces the skin's, still scaled.
    p.melanin_jitter = 0;
    p.pigment.kind = FurParams::Pigment::Kind::melanin;
    p.pigment.eumelanin = 0.1f;
    p.pigment.pheomelanin = 1.6f;
    const Strands own = grow_fur(p, strip.mesh(), lookup);
    for (size_t i = 0; i < own.size(); ++i)
        expect_near(own.sigma_a[i], melanin_sigma_a(0.2f, 3.2f), 1e-5f);
}

TEST(FurGrow, StrandsStartAtTheRootWithTheCombAngleLengthAndRadii) {
    const Strip strip;
    FurParams p;
    p.density = 200;
    p.segments = 8;
    p.length = 0.3f;
    p.length_variation = 0;
    p.comb_direction = {1, 2, 0};  // projected onto the plane: +x
    p.comb_angle_deg = 30;
    p.comb_jitter_deg = 0;
    p.root_radius = 0.01f;
    p.tip_radius = 0.002f;
    for (const auto curve : {FurParams::Curve::round, FurParams::Curve::flat}) {
        p.curve = curve;
        const Strands s = grow_fur(p, strip.mesh(), no_pigment);
        const bool round = curve == FurParams::Curve::round;
        ASSERT_EQ(s.points_per_strand, uint32_t(round ? 11 : 9));
        for (size_t i = 0; i < s.size(); ++i) {
            const float *P = &s.points[i * s.points_per_strand * 4];
            auto pt = [&](int k) { return Vec3f{P[4 * k], P[4 * k + 1], P[4 * k + 2]}; };
            // The curve's first point: the B-spline (P0 + 4 P1 + P2)/6, or P0.
            const Vec3f start =
                round ? divide_exactly(pt(0) + pt(1) * 4 + pt(2), 6) : pt(0);
            const int first = round ? 1 : 0;  // the polyline's root in the array
            EXPECT_NEAR(start.y, 0.0f, 1e-6f);
            EXPECT_NEAR(start.x, pt(first).x, 1e-5f);
            // Without gravity or curl the strand is straight: length L, 30° to the skin.
            const Vec3f tip = pt(first + 8),
                        d = divide_exactly(tip - pt(first), p.length);
            EXPECT_NEAR(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1.0f, 1e-4f);
            EXPECT_NEAR(d.y, 0.5f, 1e-4f);              // sin 30°
            EXPECT_NEAR(d.x, std::sqrt(0.75f), 1e-4f);  // combed along +x
            EXPECT_FLOAT_EQ(P[4 * first + 3], p.root_radius);
            EXPECT_FLOAT_EQ(P[4 * (first + 8) + 3], p.tip_radius);
        }
    }
}

TEST(FurGrow, GravityBendsStrandsButNeverIntoTheSkin) {
    const Strip strip;
    FurParams p;
    p.density = 300;
    p.gravity = 5;
    p.curve = FurParams::Curve::flat;
    const Strands s = grow_fur(p, strip.mesh(), no_pigment);
    float lowest_tip = 1;
    for (size_t i = 0; i < s.size(); ++i) {
        const float *P = &s.points[i * s.points_per_strand * 4];
        for (uint32_t k = 0; k < s.points_per_strand; ++k) EXPECT_GE(P[4 * k + 1], 0.0f);
        lowest_tip = std::min(lowest_tip, P[4 * p.segments + 1]);
    }
    // Bent flat: a tip far lower than a straight 30° strand's (L/2).
    EXPECT_LT(lowest_tip, 0.25f * p.length);
}

TEST(FurGrow, RefusesMoreStrandsThanMaxStrands) {
    const Strip strip;
    FurParams p;
    p.density = 1e6;
    p.max_strands = 1000;
    EXPECT_THROW(grow_fur(p, strip.mesh(), no_pigment), std::invalid_argument);
}

}  // namespace
}  // namespace pelage::renderer
