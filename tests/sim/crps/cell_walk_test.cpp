// The cell-in-triangle walk (Teo §5.2): cells never leave the surface, and on a flat
// mesh the walk is an exact translation.
#include "sim/crps/cell_walk.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/random.h"
#include "sim/crps/surface.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

// Rounding on the shared edge leaves points at most a few ulps outside; clamping keeps
// them within 1e-9 in barycentric terms.
constexpr double inside_tolerance = 1e-9;

void random_walks(const Surface &s, double step_scale, int walkers, int steps) {
    const Crps &crps = s.crps;
    for (int w = 0; w < walkers; ++w) {
        CounterRng rng(7, RandomStream::division, w);
        SurfacePoint p{static_cast<TriId>(rng.next_u64() % crps.num_triangles()), {}};
        for (int k = 0; k < steps; ++k) {
            const double len = step_scale * rng.uniform() * 4,
                         angle = 6.283185307179586 * rng.uniform();
            p = walk(crps, p, {len * std::cos(angle), len * std::sin(angle)});
            ASSERT_LT(p.tri, crps.num_triangles());
            ASSERT_GE(min_barycentric(crps.frame(p.tri), p.p), -inside_tolerance)
                << "walker " << w << " step " << k;
            ASSERT_TRUE(is_finite(crps.to_3d(p.tri, p.p)));
        }
    }
}

double mean_sqrt_area(const Surface &s) {
    return std::sqrt(s.mesh.surface_area() / double(s.mesh.num_triangles()));
}

TEST(CellWalk, CellsNeverLeaveTheCow) {
    const Surface s = build_surface(test::sample_mesh("cow.off"));
    random_walks(s, mean_sqrt_area(s), 200, 200);
}

TEST(CellWalk, BoundaryEdgesStopCellsOnAnOpenMesh) {
    const Surface s = build_surface("procedural:plane:6x6");
    random_walks(s, mean_sqrt_area(s), 100, 100);
    // A huge push ends on the boundary, still on the surface.
    SurfacePoint p{0, {}};
    p = walk(s.crps, p, {1e3, 2e3});
    EXPECT_GE(min_barycentric(s.crps.frame(p.tri), p.p), -inside_tolerance);
    const Bounds3 b = s.mesh.bounds();
    const Vec3d q = s.crps.to_3d(p.tri, p.p);
    EXPECT_GE(q.x, b.lo.x - 1e-9);
    EXPECT_LE(q.x, b.hi.x + 1e-9);
    EXPECT_GE(q.z, b.lo.z - 1e-9);
    EXPECT_LE(q.z, b.hi.z + 1e-9);
}

TEST(CellWalk, FlatMeshWalkIsAnExactTranslation) {
    // The unfolding of a plane is the identity, so walking several triangles moves the
    // point by exactly |d| in 3D.
    const Surface s = build_surface("procedural:plane:8x8");
    TriId centre = 0;
    double best = 1e300;
    for (TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        const Vec3d c = s.crps.to_3d(t, {0, 0});
        if (length_squared(c) < best) {
            best = length_squared(c);
            centre = t;
        }
    }
    const Vec3d start = s.crps.to_3d(centre, {0, 0});
    for (int k = 0; k < 16; ++k) {
        const double angle = 0.39 * k,
                     len = 0.3;  // the plane spans [-1, 1]^2: stays inside
        const SurfacePoint p = walk(s.crps, {centre, {0, 0}},
                                    {len * std::cos(angle), len * std::sin(angle)});
        const Vec3d end = s.crps.to_3d(p.tri, p.p);
        EXPECT_NEAR(length(end - start), len, 1e-9) << "direction " << k;
    }
}

}  // namespace
}  // namespace pelage::sim
