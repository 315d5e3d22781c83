// Window propagation against closed-form geodesics: a plane (straight lines), a cube
// (unfoldings across one and two edges) and a plane with a square hole (paths bend
// around the hole's corners: pseudo-sources with σ > 0).
#include "sim/geodesic/window_propagation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim/crps/surface.h"
#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

// The point of `mesh` nearest to p, as (triangle, local 2D point): p must lie on it.
struct Located {
    TriId tri;
    Vec2d p;
};
Located locate(const Surface &s, Vec3d p) {
    for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        const Vec2d q = s.crps.to_2d(t, p);
        if (length(s.crps.to_3d(t, q) - p) > 1e-9) continue;  // not on t's plane
        const Vec3d b = s.crps.to_barycentric(t, q);
        if (b.x >= -1e-12 && b.y >= -1e-12 && b.z >= -1e-12) return {t, q};
    }
    ADD_FAILURE() << "point not on the mesh";
    return {0, {}};
}

double geodesic(const Surface &s, const GeodesicMesh &g, Vec3d from, Vec3d to,
                double radius) {
    WindowPropagation prop(g);
    std::vector<GeodesicWindow> windows;
    const Located a = locate(s, from), b = locate(s, to);
    prop.run(a.tri, a.p, radius, windows);
    std::vector<GeodesicWindow> on_b;
    for (const GeodesicWindow &w : windows)
        if (w.face == b.tri) on_b.push_back(w);
    return distance_from_windows(on_b.data(), on_b.data() + on_b.size(), b.p);
}

TEST(WindowPropagation, PlaneDistancesAreStraightLines) {
    const Surface s = build_surface(make_plane(9, 7, 3, 2));
    const GeodesicMesh g(s.crps);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> x(-1.5, 1.5), z(-1, 1);
    for (int i = 0; i < 40; ++i) {
        const Vec3d a{x(rng), 0, z(rng)}, b{x(rng), 0, z(rng)};
        EXPECT_NEAR(geodesic(s, g, a, b, 10), length(a - b), 1e-9);
    }
}

TEST(WindowPropagation, RadiusBoundsTheSettledWindows) {
    const Surface s = build_surface(make_plane(20, 20, 4, 4));
    const GeodesicMesh g(s.crps);
    WindowPropagation prop(g);
    std::vector<GeodesicWindow> windows;
    const Located a = locate(s, {0.1, 0, 0.2});
    prop.run(a.tri, a.p, 0.5, windows);
    std::vector<char> reached(s.mesh.num_triangles(), 0);
    for (const GeodesicWindow &w : windows) {
        EXPECT_LE(w.min_distance, 0.5);
        reached[w.face] = 1;
    }
    // Every triangle with a point within the radius has a window; none farther.
    for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        double nearest = 1e300;
        for (int i = 0; i <= 20; ++i)
            for (int j = 0; i + j <= 20; ++j) {
                const double b1 = i / 20.0, b2 = j / 20.0;
                const Vec3d p = s.mesh.vertex(t, 0) * (1 - b1 - b2) +
                                s.mesh.vertex(t, 1) * b1 + s.mesh.vertex(t, 2) * b2;
                nearest = std::min(nearest, length(p - Vec3d{0.1, 0, 0.2}));
            }
        if (nearest < 0.49) {
            EXPECT_TRUE(reached[t]) << t;
        }
        if (nearest > 0.51) {
            EXPECT_FALSE(reached[t]) << t;
        }
    }
}

TriangleMesh unit_cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({double(i & 1), double(i >> 1 & 1), double(i >> 2)});
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &q : quads) {
        m.triangles.push_back({VertId(q[0]), VertId(q[1]), VertId(q[2])});
        m.triangles.push_back({VertId(q[0]), VertId(q[2]), VertId(q[3])});
    }
    return m;
}

TEST(WindowPropagation, CubeDistancesAreTheShortestUnfoldings) {
    const Surface s = build_surface(unit_cube());
    const GeodesicMesh g(s.crps);
    EXPECT_EQ(g.num_pseudo_sources(), 0u);  // every corner is convex (3π/2)
    // Centres of opposite faces: up, across and down.
    EXPECT_NEAR(geodesic(s, g, {0.5, 0.5, 0}, {0.5, 0.5, 1}, 10), 2.0, 1e-9);
    // Adjacent faces, unfolded about their shared edge (x = 1, z = 0).
    EXPECT_NEAR(geodesic(s, g, {0.2, 0.3, 0}, {1, 0.6, 0.7}, 10),
                std::hypot(1.7 - 0.2, 0.6 - 0.3), 1e-9);
    // Opposite faces, off centre: the shortest way crosses two side faces (x = 0, then
    // y = 1), whose unfolding puts b at (y_b - 2, 1 + x_b) in the bottom face's plane.
    EXPECT_NEAR(geodesic(s, g, {0.2, 0.3, 0}, {0.6, 0.9, 1}, 10),
                std::hypot(0.9 - 2 - 0.2, 1 + 0.6 - 0.3), 1e-9);
}

TEST(WindowPropagation, PathsBendAroundTheCornersOfAHole) {
    // [-2, 2]² in steps of 0.5 without the square [-0.5, 0.5]²: the path from (-1, 0) to
    // (1, 0) goes round two corners of the hole.
    TriangleMesh m = make_plane(8, 8, 4, 4);
    TriangleMesh holed;
    holed.positions = m.positions;
    for (TriId t = 0; t < m.num_triangles(); ++t) {
        const Vec3d c = (m.vertex(t, 0) + m.vertex(t, 1) + m.vertex(t, 2)) / 3.0;
        if (std::abs(c.x) < 0.5 && std::abs(c.z) < 0.5) continue;
        holed.triangles.push_back(m.triangles[t]);
    }
    const Surface s = build_surface(holed);
    const GeodesicMesh g(s.crps);
    EXPECT_NEAR(geodesic(s, g, {-1, 0, 0}, {1, 0, 0}, 10), 1 + 2 * std::sqrt(0.5), 1e-9);
    // Seen past one corner only: (-1, 0) to (0.25, 1) bends at (-0.5, 0.5).
    EXPECT_NEAR(geodesic(s, g, {-1, 0, 0}, {0.25, 0, 1}, 10),
                std::sqrt(0.5) + std::hypot(0.75, 0.5), 1e-9);
    // In plain sight: a straight line.
    EXPECT_NEAR(geodesic(s, g, {-1, 0, 0.6}, {1, 0, 0.9}, 10), std::hypot(2.0, 0.3),
                1e-9);
}

}  // namespace
}  // namespace pelage::sim
