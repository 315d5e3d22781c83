// Breadth-first unfolding: exact on a plane, isometric on a developable cylinder.
#include "sim/crps/unfold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sim/crps/surface.h"
#include "sim/mesh/closest_point.h"
#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

TEST(Unfold, PlaneReproducesTheTrue2DLayout) {
    const Surface s = build_surface(make_plane(12, 12, 3, 3));
    UnfoldScratch scratch;
    std::vector<UnfoldedTriangle> out;
    for (TriId master : {TriId(0), TriId(77), TriId(143)}) {
        unfold_around_triangle(s.crps, master, 1.0, out, scratch);
        ASSERT_GT(out.size(), 20u);
        for (const UnfoldedTriangle &u : out)
            for (int c = 0; c < 3; ++c) {
                // Coplanar: the true layout is the master frame's own projection.
                const Vec2d truth = s.crps.to_2d(master, s.mesh.vertex(u.tri, c));
                ASSERT_LT(length(u.to_master.apply(s.crps.frame(u.tri).v[c]) - truth),
                          1e-12);
            }
    }
}

TEST(Unfold, RadiusSelectsExactlyTheTrianglesWithinIt) {
    const Surface s = build_surface(make_plane(16, 16, 4, 4));
    UnfoldScratch scratch;
    std::vector<UnfoldedTriangle> out;
    const TriId master = 250;
    const double radius = 0.6;
    unfold_around_triangle(s.crps, master, radius, out, scratch);
    const Vec2d *m = s.crps.frame(master).v.data();
    size_t expected = 0;
    for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        Vec2d tri[3];
        for (int c = 0; c < 3; ++c) tri[c] = s.crps.to_2d(master, s.mesh.vertex(t, c));
        expected += triangle_triangle_distance(m, tri) <= radius;
    }
    EXPECT_EQ(out.size(), expected);
    for (const UnfoldedTriangle &u : out) EXPECT_LE(u.distance, radius);
}

// A faceted cylinder is developable: unrolling it is an isometry, so distances between
// points on unfolded neighbours equal their distances on the unrolled strip.
TEST(Unfold, CylinderPreservesGeodesicDistances) {
    const int around = 24, along = 6;
    const double radius = 1.0, height = 2.0;
    const Surface s = build_surface(make_cylinder(around, along, radius, height));
    const double chord = 2 * radius * std::sin(std::numbers::pi / around);
    // Unrolled coordinates (arc length along the polygon, height) of each mesh vertex.
    auto unrolled = [&](VertId v, int near_column) {
        const int i = int(v) / around;
        int j = int(v) % around;
        while (j - near_column > around / 2) j -= around;
        while (near_column - j > around / 2) j += around;
        return Vec2d{j * chord, height * (double(i) / along - 0.5)};
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u01(0, 1);
    auto random_bary = [&] {
        double a = u01(rng), b = u01(rng);
        if (a + b > 1) {
            a = 1 - a;
            b = 1 - b;
        }
        return Vec3d{1 - a - b, a, b};
    };
    UnfoldScratch scratch;
    std::vector<UnfoldedTriangle> out;
    size_t pairs = 0;
    for (TriId master = 0; master < s.mesh.num_triangles(); master += 7) {
        unfold_around_triangle(s.crps, master, 0.5, out, scratch);
        const int column = int(s.mesh.triangles[master][0]) % around;
        for (const UnfoldedTriangle &t : out) {
            for (int n = 0; n < 4; ++n) {
                const Vec3d bp = random_bary(), bq = random_bary();
                const Vec2d p = s.crps.barycentric_to_2d(master, bp);
                const Vec2d q = t.to_master.apply(s.crps.barycentric_to_2d(t.tri, bq));
                Vec2d up, uq;
                for (int c = 0; c < 3; ++c) {
                    up += unrolled(s.mesh.triangles[master][c], column) * bp[c];
                    uq += unrolled(s.mesh.triangles[t.tri][c], column) * bq[c];
                }
                ASSERT_NEAR(length(p - q), length(up - uq), 1e-12);
                ++pairs;
            }
        }
    }
    EXPECT_GT(pairs, 1000u);
}

TEST(Unfold, PointUnfoldingContainsTheTrianglesNearThePoint) {
    const Surface s = build_surface(make_icosphere(3));
    UnfoldScratch scratch;
    std::vector<UnfoldedTriangle> around_tri, around_pt;
    const TriId master = 100;
    unfold_around_triangle(s.crps, master, 0.2, around_tri, scratch);
    unfold_around_point(s.crps, master, Vec2d{0, 0}, 0.2, around_pt, scratch);
    // The centroid is inside the master: every triangle near it is near the master.
    EXPECT_LE(around_pt.size(), around_tri.size());
    EXPECT_GT(around_pt.size(), 5u);
    EXPECT_EQ(around_pt[0].tri, master);
    EXPECT_EQ(around_pt[0].depth, 0u);
}

TEST(Unfold, DistanceHelpersAreExact) {
    const Vec2d a[3] = {{0, 0}, {1, 0}, {0, 1}};
    const Vec2d b[3] = {{2, 0}, {3, 0}, {2, 1}};
    EXPECT_DOUBLE_EQ(triangle_triangle_distance(a, b), 1.0);
    const Vec2d star[3] = {
        {0.2, -0.2}, {0.6, 0.8}, {-0.2, 0.4}};  // edges cross, no corner inside
    EXPECT_EQ(triangle_triangle_distance(a, star), 0.0);
    EXPECT_DOUBLE_EQ(point_triangle_distance({0.25, 0.25}, a), 0.0);
    EXPECT_DOUBLE_EQ(point_triangle_distance({-3, 0.5}, a), 3.0);
}

}  // namespace
}  // namespace pelage::sim
