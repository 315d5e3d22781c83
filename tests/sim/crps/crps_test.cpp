// The CRPS (Teo 2006 ch. 4): exact conversions, and neighbour maps that unfold.
#include <gtest/gtest.h>

#include <random>

#include "sim/crps/crps_validation.h"
#include "sim/crps/surface.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

// The required bound: 1e-5 of the bounding-box diagonal. Double precision gives ~1e-15,
// so a real bug (wrong rotation, wrong centre, a swapped corner) is far above it.
constexpr double tolerance = 1e-5;

Surface cow() { return build_surface(test::sample_mesh("cow.off")); }
Surface sphere760() { return build_surface(make_uv_sphere(20, 20)); }

TEST(Crps, RoundTripWithin1em5OfDiagonalOnCowAndSphere) {
    for (const Surface &s : {cow(), sphere760()}) {
        const CrpsValidation v = validate_crps(s.mesh, s.crps);
        EXPECT_LT(v.roundtrip_max_error, tolerance);
        EXPECT_LT(v.barycentric_max_error, tolerance);
    }
}

TEST(Crps, ReferenceTriangleIsTheFaceRotatedNormalUp) {
    const Surface s = cow();
    for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        const CrpsFrame &f = s.crps.frame(t);
        const Vec3d up = f.rotation * f.normal;
        ASSERT_NEAR(up.y, 1.0, 1e-12);
        // Same side lengths in 2D as in 3D, centroid at the origin.
        for (int c = 0; c < 3; ++c) {
            const double l3 = length(s.mesh.vertex(t, (c + 1) % 3) - s.mesh.vertex(t, c));
            ASSERT_NEAR(length(f.v[(c + 1) % 3] - f.v[c]), l3, 1e-12);
        }
        const Vec2d c = (f.v[0] + f.v[1] + f.v[2]) / 3.0;
        ASSERT_NEAR(length(c), 0.0, 1e-12);
    }
}

TEST(Crps, EdgeNeighboursShareEndpointsAndKeepLengths) {
    for (const Surface &s : {cow(), sphere760()}) {
        const CrpsValidation v = validate_crps(s.mesh, s.crps);
        EXPECT_LT(v.edge_map_max_error, tolerance);
        EXPECT_LT(v.vertex_map_max_error, tolerance);
        EXPECT_LT(v.edge_length_max_error, tolerance);
        EXPECT_GT(v.maps_checked, 9000u);
    }
}

// An edge map unfolds: j's third corner lands on the other side of the shared edge from
// i's third corner (a fold-over would put both on the same side).
TEST(Crps, EdgeNeighboursUnfoldToTheOtherSide) {
    const Surface s = sphere760();
    const Topology &topo = s.crps.topology();
    for (TriId i = 0; i < s.mesh.num_triangles(); ++i) {
        const auto nb = topo.primary_neighbours(i);
        for (size_t k = 0; k < nb.size(); ++k) {
            const TriId j = nb[k];
            const auto &ti = s.mesh.triangles[i], &tj = s.mesh.triangles[j];
            int ci = -1, cj = -1;  // the corners not on the shared edge
            for (int c = 0; c < 3; ++c) {
                if (std::find(tj.begin(), tj.end(), ti[c]) == tj.end()) ci = c;
                if (std::find(ti.begin(), ti.end(), tj[c]) == ti.end()) cj = c;
            }
            const CrpsFrame &fi = s.crps.frame(i);
            const Vec2d a = fi.v[(ci + 1) % 3], b = fi.v[(ci + 2) % 3];
            const Vec2d other = s.crps.to_master(i)[k].apply(s.crps.frame(j).v[cj]);
            EXPECT_LT(cross(b - a, fi.v[ci] - a) * cross(b - a, other - a), 0.0);
        }
    }
}

TEST(Crps, MapsComposeWithTheirInverseToIdentity) {
    const Surface s = cow();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (TriId i = 0; i < s.mesh.num_triangles(); ++i) {
        const auto fwd = s.crps.to_master(i), back = s.crps.to_neighbour(i);
        const auto nb = s.crps.topology().neighbours(i);
        for (size_t k = 0; k < fwd.size(); ++k) {
            const RigidMap2 id = compose(back[k], fwd[k]);
            ASSERT_NEAR(id.c, 1.0, 1e-12);
            ASSERT_NEAR(id.s, 0.0, 1e-12);
            ASSERT_NEAR(id.ax, 0.0, 1e-12);
            ASSERT_NEAR(id.ay, 0.0, 1e-12);
            // The map stored at j for i is the same inverse.
            RigidMap2 i_to_j;
            ASSERT_TRUE(s.crps.find_map(nb[k], i, &i_to_j));
            const Vec2d p{u(rng) * 0.05, u(rng) * 0.05};
            ASSERT_LT(length(i_to_j.apply(p) - back[k].apply(p)), 1e-12);
        }
    }
}

// Teo §4.1: a vertex neighbour rotates about the line where the two planes meet. That
// line's points are on both triangles' planes, so they must land on themselves.
TEST(Crps, VertexNeighboursRotateAboutThePlanesIntersectionLine) {
    const Surface s = sphere760();
    const Topology &topo = s.crps.topology();
    for (TriId i = 0; i < s.mesh.num_triangles(); ++i) {
        const auto nb = topo.neighbours(i);
        for (size_t k = topo.num_primary[i]; k < nb.size(); ++k) {
            const TriId j = nb[k];
            const CrpsFrame &fi = s.crps.frame(i), &fj = s.crps.frame(j);
            const Vec3d d = cross(fi.normal, fj.normal);
            if (length(d) < 1e-6) continue;
            VertId v = 0;
            for (VertId a : s.mesh.triangles[i])
                for (VertId b : s.mesh.triangles[j])
                    if (a == b) v = a;
            const Vec3d on_line = s.mesh.positions[v] + normalize(d) * 0.1;
            const Vec2d in_j = s.crps.to_2d(j, on_line), in_i = s.crps.to_2d(i, on_line);
            ASSERT_LT(length(s.crps.to_master(i)[k].apply(in_j) - in_i), 1e-12);
        }
    }
}

TEST(Crps, CoplanarVertexNeighboursAlignExactly) {
    const Surface s = build_surface(make_plane(6, 6, 2, 2));
    const CrpsValidation v = validate_crps(s.mesh, s.crps);
    EXPECT_LT(v.vertex_map_max_error, 1e-14);
}

}  // namespace
}  // namespace pelage::sim
