// The greedy collapse (sim/remesh/greedy_collapse.h) and the topology count it checks
// itself with (surface_topology.h). The topology is checked with the tests' own count
// (surface_reference.h), distances by brute force with Ericson's closest point, and the
// vertices against the input's own.

#include "sim/remesh/greedy_collapse.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "sim/mesh/mesh_load.h"
#include "sim/mesh/procedural_mesh.h"
#include "sim/mesh/subdivide.h"
#include "sim/remesh/surface_topology.h"
#include "tests/sim/remesh/surface_reference.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

using test::distance_to_mesh;
using test::euler_and_open_edges;

double mean_edge(const TriangleMesh &m) {
    double sum = 0;
    for (TriId t = 0; t < m.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c)
            sum += length(m.vertex(t, (c + 1) % 3) - m.vertex(t, c));
    return sum / (3.0 * double(m.num_triangles()));
}

TEST(SurfaceTopology, CountsTheCowAsTheIndependentCountDoes) {
    const TriangleMesh cow = load_mesh(test::sample_mesh("cow.off"));
    const SurfaceTopology top = surface_topology(cow);
    EXPECT_TRUE(top.edge_manifold);
    EXPECT_EQ(top.euler, euler_and_open_edges(cow).first);
    EXPECT_EQ(top.euler, 2);  // a sphere, once its one pinched vertex is split
    EXPECT_EQ(top.pinched, 1);
    EXPECT_EQ(top.components, 1);
    EXPECT_EQ(top.boundary_loops, 0);
}

TEST(GreedyCollapse, ADenseCowComesDownAndKeepsItsTopologyAndItsVertices) {
    const TriangleMesh cow = load_mesh(test::sample_mesh("cow.off"));
    const TriangleMesh dense =
        subdivide(subdivide(cow, Subdivision::midpoint), Subdivision::midpoint);
    const double diagonal = dense.bounds().diagonal();
    const GreedyCollapseOptions options{4 * mean_edge(dense), 0.002 * diagonal};
    std::string why;
    const auto out = greedy_collapse(dense, options, &why);
    ASSERT_TRUE(out) << why;
    EXPECT_LT(out->num_triangles() * 6, dense.num_triangles());
    EXPECT_EQ(euler_and_open_edges(*out), euler_and_open_edges(dense));
    // Every vertex is one of the input's, unmoved.
    std::set<std::array<double, 3>> input;
    for (const Vec3d &p : dense.positions) input.insert({p.x, p.y, p.z});
    for (const Vec3d &p : out->positions) EXPECT_TRUE(input.count({p.x, p.y, p.z}));
    // The input's vertices stay within the bound of the result.
    double worst = 0;
    for (size_t v = 0; v < dense.num_vertices(); v += 13)
        worst = std::max(worst, distance_to_mesh(dense.positions[v], *out));
    EXPECT_LE(worst, options.max_distance * (1 + 1e-9));
    // Faces keep the input's orientation: the enclosed volume stays.
    const auto volume = [](const TriangleMesh &m) {
        double v = 0;
        for (TriId t = 0; t < m.num_triangles(); ++t)
            v += dot(m.vertex(t, 0), cross(m.vertex(t, 1), m.vertex(t, 2))) / 6;
        return v;
    };
    EXPECT_NEAR(volume(*out) / volume(dense), 1.0, 0.03);
    // The same input gives the same mesh.
    const auto again = greedy_collapse(dense, options);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->positions, out->positions);
    EXPECT_EQ(again->triangles, out->triangles);
}

// A closed tube of radius 0.01 and length 1, its rings 0.002 apart: edges of 0.05 would
// flatten it into a ribbon or a stub if only the normals were watched.
TriangleMesh thin_tube() {
    TriangleMesh m;
    const int around = 24, rings = 501;
    for (int i = 0; i < rings; ++i)
        for (int k = 0; k < around; ++k) {
            const double a = 2 * M_PI * k / around;
            m.positions.push_back({0.01 * std::cos(a), 0.01 * std::sin(a), 0.002 * i});
        }
    const auto at = [&](int i, int k) { return VertId(i * around + (k % around)); };
    for (int i = 0; i + 1 < rings; ++i)
        for (int k = 0; k < around; ++k) {
            m.triangles.push_back({at(i, k), at(i, k + 1), at(i + 1, k + 1)});
            m.triangles.push_back({at(i, k), at(i + 1, k + 1), at(i + 1, k)});
        }
    // Caps: a fan around each end's centre.
    for (const int i : {0, rings - 1}) {
        const VertId centre = VertId(m.positions.size());
        m.positions.push_back({0, 0, 0.002 * i});
        for (int k = 0; k < around; ++k)
            m.triangles.push_back(
                i == 0 ? std::array<VertId, 3>{centre, at(i, k + 1), at(i, k)}
                       : std::array<VertId, 3>{centre, at(i, k), at(i, k + 1)});
    }
    return m;
}

TEST(GreedyCollapse, AThinTubeKeepsItsShapeWithinTheBound) {
    const TriangleMesh tube = thin_tube();
    ASSERT_EQ(surface_topology(tube).euler, 2);
    ASSERT_EQ(surface_topology(tube).boundary_loops, 0);
    const GreedyCollapseOptions options{0.05, 0.002};
    std::string why;
    const auto out = greedy_collapse(tube, options, &why);
    ASSERT_TRUE(out) << why;
    EXPECT_LT(out->num_triangles() * 4, tube.num_triangles());
    EXPECT_EQ(euler_and_open_edges(*out), euler_and_open_edges(tube));
    double worst = 0;
    for (const Vec3d &p : tube.positions)
        worst = std::max(worst, distance_to_mesh(p, *out));
    EXPECT_LE(worst, options.max_distance * (1 + 1e-9));
    // Without the bound the tube is flattened: its radius, 0.01, is the distance.
    const auto loose = greedy_collapse(tube, {0.05, 1.0});
    ASSERT_TRUE(loose);
    double loose_worst = 0;
    for (const Vec3d &p : tube.positions)
        loose_worst = std::max(loose_worst, distance_to_mesh(p, *loose));
    EXPECT_GT(loose_worst, 2 * options.max_distance);
}

// A unit disk as a polar grid: a pole of `sectors` faces at the centre (a fanned cap),
// rings 1/rings apart.
TriangleMesh polar_disk(int sectors, int rings) {
    TriangleMesh m;
    m.positions.push_back({0, 0, 0});
    for (int i = 1; i <= rings; ++i)
        for (int k = 0; k < sectors; ++k) {
            const double a = 2 * M_PI * k / sectors, r = double(i) / rings;
            m.positions.push_back({r * std::cos(a), r * std::sin(a), 0});
        }
    const auto at = [&](int i, int k) {
        return VertId(1 + (i - 1) * sectors + k % sectors);
    };
    for (int k = 0; k < sectors; ++k) m.triangles.push_back({0, at(1, k), at(1, k + 1)});
    for (int i = 1; i < rings; ++i)
        for (int k = 0; k < sectors; ++k) {
            m.triangles.push_back({at(i, k), at(i + 1, k), at(i + 1, k + 1)});
            m.triangles.push_back({at(i, k), at(i + 1, k + 1), at(i, k + 1)});
        }
    return m;
}

TEST(GreedyCollapse, ADiskAroundAPoleComesDownAndKeepsItsRim) {
    const TriangleMesh disk = polar_disk(1000, 40);
    const auto out = greedy_collapse(disk, {0.04, 0.001});
    ASSERT_TRUE(out);
    EXPECT_LT(out->num_triangles() * 2, disk.num_triangles());
    EXPECT_EQ(euler_and_open_edges(*out), euler_and_open_edges(disk));
    // The rim, a boundary, is whole.
    const auto has = [&](Vec3d p) {
        return std::find(out->positions.begin(), out->positions.end(), p) !=
               out->positions.end();
    };
    for (int k = 0; k < 1000; k += 37)
        EXPECT_TRUE(has(disk.positions[1 + 39 * 1000 + k]));
}

TEST(GreedyCollapse, RefusesAnInputWithAnEdgeOfThreeFaces) {
    TriangleMesh fin;
    fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    EXPECT_FALSE(surface_topology(fin).edge_manifold);
    std::string why;
    EXPECT_FALSE(greedy_collapse(fin, {0.1, 0.1}, &why));
    EXPECT_NE(why.find("three faces"), std::string::npos) << why;
}

}  // namespace
}  // namespace pelage::sim
