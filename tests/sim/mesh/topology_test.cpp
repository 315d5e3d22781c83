// Topology: edges, fans, neighbours and orientation against brute-force definitions.
#include "sim/mesh/topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "sim/mesh/mesh_clean.h"
#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

int shared_vertices(const TriangleMesh &m, TriId a, TriId b) {
    int n = 0;
    for (VertId u : m.triangles[a])
        for (VertId v : m.triangles[b]) n += u == v;
    return n;
}

TEST(Topology, ClosedSphereIsManifoldWithEulerCharacteristic2) {
    const TriangleMesh m = make_uv_sphere(20, 20);
    const Topology t = build_topology(m);
    EXPECT_EQ(m.num_triangles(), 760u);
    EXPECT_EQ(t.num_edges() * 2, m.num_triangles() * 3);
    EXPECT_EQ(
        int64_t(m.num_vertices()) - int64_t(t.num_edges()) + int64_t(m.num_triangles()),
        2);
    EXPECT_EQ(t.boundary_edges, 0u);
    EXPECT_EQ(t.nonmanifold_edges, 0u);
    EXPECT_EQ(t.nonmanifold_vertices, 0u);
    EXPECT_EQ(t.num_components, 1u);
    EXPECT_EQ(t.nonorientable_edges, 0u);
}

TEST(Topology, NeighboursMatchTheBruteForceDefinition) {
    const TriangleMesh m = make_torus(12, 8, 1.0, 0.3);
    const Topology t = build_topology(m);
    for (TriId a = 0; a < m.num_triangles(); ++a) {
        std::set<TriId> primary, secondary;
        for (TriId b = 0; b < m.num_triangles(); ++b) {
            if (b == a) continue;
            const int s = shared_vertices(m, a, b);
            if (s == 2) primary.insert(b);
            if (s == 1) secondary.insert(b);
        }
        const auto p = t.primary_neighbours(a);
        EXPECT_EQ(std::set<TriId>(p.begin(), p.end()), primary);
        const auto all = t.neighbours(a);
        EXPECT_EQ(std::set<TriId>(all.begin() + p.size(), all.end()), secondary);
    }
}

TEST(Topology, FansAreOrderedRingsOnClosedAndOpenMeshes) {
    for (const TriangleMesh &m : {make_icosphere(2), make_plane(5, 4, 1, 1)}) {
        const Topology t = build_topology(m);
        for (VertId v = 0; v < m.num_vertices(); ++v) {
            ASSERT_TRUE(t.fan_ordered[v]) << v;
            const auto fan = t.fan_of(v);
            size_t expected = 0;
            for (TriId f = 0; f < m.num_triangles(); ++f)
                expected += std::count(m.triangles[f].begin(), m.triangles[f].end(), v);
            ASSERT_EQ(fan.size(), expected);
            // Consecutive faces share an edge through v.
            for (size_t k = 0; k + 1 < fan.size(); ++k)
                EXPECT_EQ(shared_vertices(m, fan[k], fan[k + 1]), 2) << "vertex " << v;
        }
    }
}

TEST(Topology, PlaneBoundaryIsCounted) {
    const Topology t = build_topology(make_plane(5, 4, 1, 1));
    EXPECT_EQ(t.boundary_edges, 2u * (5 + 4));
}

TEST(Topology, ThreeFacesOnOneEdgeAreNonManifoldButAccepted) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const Topology t = build_topology(m);
    EXPECT_EQ(t.nonmanifold_edges, 1u);
    EXPECT_EQ(t.primary_neighbours(0).size(), 2u);
    EXPECT_EQ(t.nonmanifold_vertices, 2u);
}

TEST(Topology, InvertedFacesAreReorientedToTheMajority) {
    TriangleMesh m = make_icosphere(1);
    std::swap(m.triangles[7][1], m.triangles[7][2]);
    std::swap(m.triangles[30][1], m.triangles[30][2]);
    const Topology t = build_topology(m);
    EXPECT_EQ(t.faces_reoriented, 2u);
    EXPECT_TRUE(t.flipped[7]);
    EXPECT_TRUE(t.flipped[30]);
    EXPECT_EQ(t.nonorientable_edges, 0u);
}

TEST(Topology, DisconnectedPiecesAreSeparateComponents) {
    TriangleMesh a = make_icosphere(0), b = make_icosphere(0);
    const VertId off = static_cast<VertId>(a.positions.size());
    for (Vec3d p : b.positions) a.positions.push_back(p + Vec3d{5, 0, 0});
    for (auto tri : b.triangles)
        a.triangles.push_back({tri[0] + off, tri[1] + off, tri[2] + off});
    EXPECT_EQ(build_topology(a).num_components, 2u);
}

}  // namespace
}  // namespace pelage::sim
