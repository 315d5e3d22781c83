// The geodesic oracle against answers that need neither CGAL nor pelage's search: the
// plane (straight lines), the unit cube (unfoldings), the sphere (great circles); and its
// patch-based nearest() against whole-mesh single-source trees.
#include "tests/oracle/exact_geodesic_oracle.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

#include "sim/mesh/mesh_load.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using sim::TriangleMesh;
using sim::Vec3d;

Vec3d interpolate(const TriangleMesh &m, const SurfaceLocation &l) {
    return m.vertex(l.tri, 0) * (1 - l.b1 - l.b2) + m.vertex(l.tri, 1) * l.b1 +
           m.vertex(l.tri, 2) * l.b2;
}

// Uniform over the triangle, on a uniformly chosen triangle.
SurfaceLocation random_location(const TriangleMesh &m, std::mt19937 &rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto tri = static_cast<sim::TriId>(rng() % m.num_triangles());
    const double r = std::sqrt(u(rng)), s = u(rng);
    return {tri, r * (1 - s), r * s};
}

std::vector<SurfaceLocation> random_locations(const TriangleMesh &m, int n,
                                              unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<SurfaceLocation> out;
    for (int i = 0; i < n; ++i) out.push_back(random_location(m, rng));
    return out;
}

// The triangle holding `p` (which must lie on the surface), by brute force: the meshes
// here are small, and the answer must not depend on any of pelage's searches.
SurfaceLocation locate(const TriangleMesh &m, Vec3d p) {
    for (sim::TriId t = 0; t < m.num_triangles(); ++t) {
        const Vec3d a = m.vertex(t, 0), e1 = m.vertex(t, 1) - a, e2 = m.vertex(t, 2) - a,
                    d = p - a;
        const Vec3d n = cross(e1, e2);
        if (std::abs(dot(d, n)) > 1e-12 * length(n)) continue;
        const double inv = 1.0 / dot(n, n);
        const double b1 = dot(cross(d, e2), n) * inv, b2 = dot(cross(e1, d), n) * inv;
        if (b1 >= -1e-12 && b2 >= -1e-12 && b1 + b2 <= 1 + 1e-12)
            return {t, std::max(b1, 0.0), std::max(b2, 0.0)};
    }
    ADD_FAILURE() << "no triangle holds (" << p.x << ", " << p.y << ", " << p.z << ")";
    return {};
}

// The surface of [0, 1]^3, each face an n x n grid of split squares, wound outwards.
TriangleMesh make_unit_cube(int n) {
    TriangleMesh m;
    std::map<std::array<int, 3>, sim::VertId> ids;
    auto vertex = [&](std::array<int, 3> g) {
        auto [it, added] = ids.emplace(g, static_cast<sim::VertId>(m.positions.size()));
        if (added)
            m.positions.push_back({double(g[0]) / n, double(g[1]) / n, double(g[2]) / n});
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= 1; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    std::array<sim::VertId, 4> q;
                    for (int c = 0; c < 4; ++c) {
                        std::array<int, 3> g{};
                        g[axis] = side * n;
                        g[u] = i + (c == 1 || c == 2);
                        g[v] = j + (c >= 2);
                        q[c] = vertex(g);
                    }
                    // (u, v, axis) is right-handed, so u then v turns counter-clockwise
                    // seen from +axis: outward on side 1, reversed on side 0.
                    if (side == 1) {
                        m.triangles.push_back({q[0], q[1], q[2]});
                        m.triangles.push_back({q[0], q[2], q[3]});
                    } else {
                        m.triangles.push_back({q[0], q[2], q[1]});
                        m.triangles.push_back({q[0], q[3], q[2]});
                    }
                }
        }
    return m;
}

double max_position_error(const TriangleMesh &m, const ExactGeodesicOracle &oracle,
                          unsigned seed) {
    double worst = 0;
    for (const SurfaceLocation &l : random_locations(m, 500, seed))
        worst = std::max(worst, length(oracle.position(l) - interpolate(m, l)));
    return worst;
}

TEST(ExactGeodesicOracle, CornerOrderMatchesPelagesOnEveryFace) {
    const TriangleMesh m = sim::make_icosphere(2);
    const ExactGeodesicOracle oracle(m);
    ASSERT_EQ(oracle.num_triangles(), m.num_triangles());
    for (sim::TriId t = 0; t < m.num_triangles(); ++t) {
        EXPECT_EQ(oracle.position({t, 0, 0}), m.vertex(t, 0)) << "triangle " << t;
        EXPECT_EQ(oracle.position({t, 1, 0}), m.vertex(t, 1)) << "triangle " << t;
        EXPECT_EQ(oracle.position({t, 0, 1}), m.vertex(t, 2)) << "triangle " << t;
    }
    EXPECT_LT(max_position_error(m, oracle, 1), 1e-14);
}

TEST(ExactGeodesicOracle, TakesEverySampleMeshInPelagesFaceOrder) {
    // cow.off has two vertices at one position, each closing its own fan; the loader's
    // weld makes them one pinch vertex, which the oracle splits again.
    const std::pair<const char *, size_t> meshes[] = {{"cow.off", 1},
                                                      {"bull.off", 0},
                                                      {"camel.off", 0},
                                                      {"triceratops.off", 0},
                                                      {"elephant.off", 0}};
    for (const auto &[name, pinches] : meshes) {
        SCOPED_TRACE(name);
        const TriangleMesh m = sim::load_mesh(sample_mesh(name));
        const ExactGeodesicOracle oracle(m);
        EXPECT_EQ(oracle.num_triangles(), m.num_triangles());
        EXPECT_EQ(oracle.split_vertices(), pinches);
        EXPECT_LT(max_position_error(m, oracle, 2), 1e-12 * m.bounds().diagonal());
    }
}

TEST(ExactGeodesicOracle, RefusesMeshesCgalWouldRenumber) {
    TriangleMesh fin;  // three triangles on one edge: not a 2-manifold
    fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    EXPECT_THROW(ExactGeodesicOracle{fin}, std::runtime_error);

    TriangleMesh flipped;  // two triangles whose shared edge runs the same way in both
    flipped.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    flipped.triangles = {{0, 1, 2}, {1, 3, 2}};
    EXPECT_NO_THROW(ExactGeodesicOracle{flipped});
    flipped.triangles = {{0, 1, 2}, {2, 3, 1}};
    EXPECT_THROW(ExactGeodesicOracle{flipped}, std::runtime_error);
}

TEST(ExactGeodesicOracle, PinchVerticesDoNotConnectTheirFans) {
    TriangleMesh bowtie;  // two triangles meeting only at vertex 0
    bowtie.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
    bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
    const ExactGeodesicOracle oracle(bowtie);
    EXPECT_EQ(oracle.split_vertices(), 1u);
    // a = (0.4, 0.2, 0) on the first triangle; the pinch is corner 0 of both triangles.
    const SurfaceLocation a{0, 0.2, 0.2}, b{1, 0.2, 0.2};
    const std::vector<SurfaceLocation> targets{{0, 0, 0}, {1, 0, 0}, b};
    const std::vector<double> d = oracle.distances(a, targets);
    EXPECT_NEAR(d[0], std::sqrt(0.2), 1e-12);
    EXPECT_EQ(d[1], std::numeric_limits<double>::infinity());  // through the other fan
    EXPECT_EQ(d[2], std::numeric_limits<double>::infinity());
}

TEST(ExactGeodesicOracle, RefusesLocationsOffTheirTriangle) {
    const TriangleMesh m = sim::make_icosphere(0);
    const ExactGeodesicOracle oracle(m);
    const SurfaceLocation good{0, 0.25, 0.25};
    EXPECT_THROW(oracle.position({20, 0.1, 0.1}), std::invalid_argument);
    EXPECT_THROW(oracle.position({0, 0.7, 0.7}), std::invalid_argument);
    EXPECT_THROW(oracle.position({0, -0.1, 0.5}), std::invalid_argument);
    const SurfaceLocation bad{0, 1.5, 0};
    EXPECT_THROW(oracle.distances(good, std::span(&bad, 1)), std::invalid_argument);
    EXPECT_THROW(oracle.nearest(std::span(&bad, 1), std::span(&good, 1)),
                 std::invalid_argument);
}

TEST(ExactGeodesicOracle, GeodesicsOnAPlaneAreStraightLines) {
    const TriangleMesh m = sim::make_plane(8, 8, 2.0, 2.0);
    const ExactGeodesicOracle oracle(m);
    const auto targets = random_locations(m, 100, 3);
    for (const SurfaceLocation &s : random_locations(m, 10, 4)) {
        const std::vector<double> d = oracle.distances(s, targets);
        ASSERT_EQ(d.size(), targets.size());
        for (size_t i = 0; i < targets.size(); ++i)
            EXPECT_NEAR(d[i], length(interpolate(m, targets[i]) - interpolate(m, s)),
                        1e-9);
    }
}

TEST(ExactGeodesicOracle, UnitCubeOppositeFacesAndCorners) {
    const TriangleMesh m = make_unit_cube(3);
    const ExactGeodesicOracle oracle(m);
    // Centre to centre of opposite faces: half a face, a side face, half a face.
    const SurfaceLocation top = locate(m, {0.5, 0.5, 1}),
                          bottom = locate(m, {0.5, 0.5, 0});
    EXPECT_NEAR(oracle.distances(top, std::span(&bottom, 1))[0], 2.0, 1e-9);
    // Corner to opposite corner: the diagonal of two faces unfolded into a 1 x 2 strip.
    const SurfaceLocation a = locate(m, {0, 0, 0}), b = locate(m, {1, 1, 1});
    EXPECT_NEAR(oracle.distances(a, std::span(&b, 1))[0], std::sqrt(5.0), 1e-9);
    // Points on one face: a straight line within the face.
    const SurfaceLocation p = locate(m, {0.1, 0.2, 1}), q = locate(m, {0.9, 0.7, 1});
    EXPECT_NEAR(oracle.distances(p, std::span(&q, 1))[0], std::hypot(0.8, 0.5), 1e-9);
}

TEST(ExactGeodesicOracle, UnitCubeAdjacentFacesUnfoldAcrossTheirEdge) {
    const TriangleMesh m = make_unit_cube(3);
    const ExactGeodesicOracle oracle(m);
    // p = (x1, y1, 1) on the top, q = (1, y2, z2) on the side x = 1. Unfolding the side
    // about the edge x = z = 1 puts q at (2 - z2, y2) in the top's plane. With x1, z2 in
    // [0.8, 1] and y1, y2 in [0.3, 0.7] that line is at most sqrt(0.32) < 0.6 long, and
    // any path over another face is longer: reaching y = 0 or y = 1 and coming back alone
    // takes at least 0.6, reaching x = 0 or z = 0 at least 0.8.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> near_edge(0.8, 1.0), middle(0.3, 0.7);
    for (int k = 0; k < 30; ++k) {
        const double x1 = near_edge(rng), y1 = middle(rng), y2 = middle(rng),
                     z2 = near_edge(rng);
        const SurfaceLocation p = locate(m, {x1, y1, 1}), q = locate(m, {1, y2, z2});
        const double unfolded = std::hypot(2 - z2 - x1, y2 - y1);
        EXPECT_NEAR(oracle.distances(p, std::span(&q, 1))[0], unfolded, 1e-9)
            << "p = (" << x1 << ", " << y1 << ", 1), q = (1, " << y2 << ", " << z2 << ")";
    }
}

TEST(ExactGeodesicOracle, IcosphereDistancesFollowGreatCircles) {
    // The polyhedron lies inside the sphere, so its geodesics run short of the great
    // circle: by 0.03 % to 0.09 % at level 4 for arcs over 0.05; 0.5 % leaves room.
    const TriangleMesh m = sim::make_icosphere(4);
    const ExactGeodesicOracle oracle(m);
    const auto targets = random_locations(m, 300, 6);
    for (const SurfaceLocation &s : random_locations(m, 3, 7)) {
        const Vec3d from = normalize(interpolate(m, s));
        const std::vector<double> d = oracle.distances(s, targets);
        for (size_t i = 0; i < targets.size(); ++i) {
            const Vec3d to = normalize(interpolate(m, targets[i]));
            const double arc = std::atan2(length(cross(from, to)), dot(from, to));
            EXPECT_NEAR(d[i], arc, 0.005 * arc + 1e-9) << "target " << i;
        }
    }
}

TEST(ExactGeodesicOracle, NearestOnAPlaneIsTheNearestInSpace) {
    const TriangleMesh m = sim::make_plane(20, 20, 2.0, 2.0);
    const ExactGeodesicOracle oracle(m);
    const auto sources = random_locations(m, 300, 10),
               targets = random_locations(m, 2000, 11);
    const std::vector<ExactGeodesicOracle::Nearest> nearest =
        oracle.nearest(sources, targets);
    ASSERT_EQ(nearest.size(), targets.size());
    for (size_t i = 0; i < targets.size(); ++i) {
        const Vec3d p = interpolate(m, targets[i]);
        double best = std::numeric_limits<double>::infinity();
        for (const SurfaceLocation &s : sources)
            best = std::min(best, length(interpolate(m, s) - p));
        ASSERT_LT(nearest[i].source, sources.size()) << "target " << i;
        EXPECT_NEAR(nearest[i].distance, best, 1e-9) << "target " << i;
        EXPECT_NEAR(length(interpolate(m, sources[nearest[i].source]) - p), best, 1e-9)
            << "target " << i;
    }
}

// The truth for each target is the argmin of one single-source tree grown from the
// target itself (geodesic distance is symmetric), over the whole mesh: independent of
// the patches nearest() works on. 5 sources take the whole-mesh path, 2 000 the patches.
TEST(ExactGeodesicOracle, NearestIsTheArgminOfSingleSourceDistances) {
    const TriangleMesh m = sim::load_mesh(sample_mesh("cow.off"));
    const ExactGeodesicOracle oracle(m);
    const double tolerance = 1e-12 * m.bounds().diagonal();
    const auto targets = random_locations(m, 30, 9);
    for (int count : {5, 2000}) {
        SCOPED_TRACE(count);
        const auto sources = random_locations(m, count, 8);
        const auto nearest = oracle.nearest(sources, targets);
        ASSERT_EQ(nearest.size(), targets.size());
        for (size_t i = 0; i < targets.size(); ++i) {
            const std::vector<double> d = oracle.distances(targets[i], sources);
            const auto best = std::min_element(d.begin(), d.end());
            ASSERT_LT(nearest[i].source, sources.size()) << "target " << i;
            EXPECT_NEAR(nearest[i].distance, *best, tolerance) << "target " << i;
            // A tie may go either way; the source named must be at the distance given.
            EXPECT_NEAR(d[nearest[i].source], nearest[i].distance, tolerance)
                << "target " << i;
        }
    }
}

TEST(ExactGeodesicOracle, OtherComponentsAreOutOfReach) {
    TriangleMesh m = sim::make_icosphere(1);
    const TriangleMesh far = sim::make_icosphere(1);
    const auto offset = static_cast<sim::VertId>(m.positions.size());
    for (Vec3d p : far.positions) m.positions.push_back(p + Vec3d{5, 0, 0});
    for (auto t : far.triangles)
        m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    const ExactGeodesicOracle oracle(m);
    const SurfaceLocation here{0, 0.3, 0.3};
    const SurfaceLocation there{static_cast<sim::TriId>(far.num_triangles() + 3), 0.3,
                                0.3};
    const std::vector<SurfaceLocation> targets{here, there};
    const std::vector<double> d = oracle.distances(here, targets);
    EXPECT_NEAR(d[0], 0.0, 1e-12);
    EXPECT_EQ(d[1], std::numeric_limits<double>::infinity());
    const auto n = oracle.nearest(std::span(&here, 1), targets);
    EXPECT_EQ(n[0].source, 0u);
    EXPECT_EQ(n[1].source, sim::invalid_id);
    EXPECT_EQ(n[1].distance, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(oracle.nearest({}, targets)[0].source == sim::invalid_id);
}

}  // namespace
}  // namespace pelage::test
