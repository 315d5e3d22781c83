// A pattern grown on the cow rendered on other meshes of its shape (surface_transfer.h):
// the cow split at its edge midpoints (the same surface), Loop-subdivided (a smoother
// one, vertices moved), scaled and moved; and a mesh of another shape refused. The
// reference is the cow's own lookup at the corresponding point: the same 3D point where
// the surfaces coincide, else the closest point over all of the cow's triangles.
#include "pattern/transfer/surface_transfer.h"

#include <gtest/gtest.h>

#include <limits>

#include "pattern/mosaic/pattern.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface_sampling.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/subdivide.h"
#include "tests/test_paths.h"

namespace pelage::pattern::transfer {
namespace {

struct Grown {
    test::TempDir tmp;
    std::string cells, cow_path = test::sample_mesh("cow.off");
    std::unique_ptr<mosaic::MosaicPattern> on_cow;
    Grown() {
        cells = test::simulate_two_type_cells(tmp, cow_path, 3000, 0.4);
        on_cow = std::make_unique<mosaic::MosaicPattern>(cells, cow_path);
    }
    // The cell type the cow's own lookup gives at triangle t, 3D point p.
    uint8_t type_on_cow(sim::TriId t, sim::Vec3d p) const {
        const sim::Crps &crps = on_cow->surface().crps;
        const sim::Vec2d q = crps.to_2d(t, p);
        const mosaic::ClosestCell c =
            on_cow->index().find_nearest(t, mosaic::Vec2f{float(q.x), float(q.y)});
        return on_cow->cells().type[c.index];
    }
    // ... at the point of the cow closest to p (every triangle tried).
    uint8_t type_near(sim::Vec3d p) const {
        const sim::TriangleMesh &m = on_cow->surface().mesh;
        double best = std::numeric_limits<double>::infinity();
        sim::TriId at = 0;
        sim::Vec3d x;
        for (sim::TriId t = 0; t < m.num_triangles(); ++t) {
            const sim::Vec3d c = closest_point_on_triangle(
                p, m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2));
            if (length(c - p) < best) best = length(c - p), at = t, x = c;
        }
        return type_on_cow(at, x);
    }
    // Share of random points of `render` where the pattern rendered on it shows the
    // reference's type; `reference(t, p)` for render triangle t and 3D point p.
    template <typename Reference>
    double agreement(const sim::TriangleMesh &render, const std::string &name, size_t n,
                     Reference reference) {
        const std::string path = tmp.file(name);
        sim::write_obj(path, render, {});
        const mosaic::MosaicPattern pattern(cells, path);
        EXPECT_NE(pattern.transfer(), nullptr);
        if (!pattern.transfer()) return 0;
        const sim::Surface r = sim::build_surface(render);
        size_t same = 0;
        for (const auto &s : sim::sample_surface_uniform(r.crps, n, 77)) {
            const sim::Vec3d b = r.crps.to_barycentric(s.tri, s.p);
            const auto at = pattern.transfer()->map(s.tri, float(b.y), float(b.z));
            const mosaic::ClosestCell c =
                pattern.index().find_nearest(at.tri, at.b1, at.b2);
            same += pattern.cells().type[c.index] ==
                    reference(s.tri, r.crps.to_3d(s.tri, s.p));
        }
        return double(same) / double(n);
    }
};

TEST(SurfaceTransfer, TheSameSurfaceSplitAtItsMidpointsShowsTheSamePattern) {
    Grown g;
    const sim::TriangleMesh split =
        sim::subdivide(g.on_cow->surface().mesh, sim::Subdivision::midpoint);
    const double a =
        g.agreement(split, "split.obj", 20000, [&](sim::TriId t, sim::Vec3d p) {
            return g.type_on_cow(t / 4, p);  // child 4t + k lies on the cow's triangle t
        });
    EXPECT_GE(a, 0.999);
    std::printf("midpoint-subdivided cow: %.4f of points show the cow's colour\n", a);
}

// The cow's own triangles, each with three corners of its own (as the renderer unwelds
// a skinned file's rest pose) and moved by round-off: the same surface, so no transfer
// (and no "grown on another mesh" note); every point shows what the cow's own lookup
// shows at that triangle and point. One vertex moved by 0.5 % is another surface.
TEST(SurfaceTransfer, TheSameTrianglesUnweldedAndRoundedNeedNoTransfer) {
    Grown g;
    ASSERT_EQ(g.on_cow->transfer(), nullptr);
    const sim::Surface &cow = g.on_cow->surface();
    sim::TriangleMesh soup;
    for (sim::TriId t = 0; t < cow.mesh.num_triangles(); ++t) {
        const sim::VertId first = sim::VertId(soup.positions.size());
        for (int c = 0; c < 3; ++c)
            soup.positions.push_back(cow.mesh.vertex(t, c) * (1 + 1e-13 * (c + 1)));
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    const mosaic::MosaicPattern pattern(g.cells, soup, "soup");
    EXPECT_EQ(pattern.transfer(), nullptr);
    ASSERT_EQ(pattern.num_triangles(), cow.mesh.num_triangles());
    const size_t n = 20000;
    size_t same = 0;
    for (const auto &s : sim::sample_surface_uniform(cow.crps, n, 9)) {
        const sim::Vec3d b = cow.crps.to_barycentric(s.tri, s.p);
        const mosaic::ClosestCell c =
            pattern.index().find_nearest(s.tri, float(b.y), float(b.z));
        same += pattern.cells().type[c.index] ==
                g.type_on_cow(s.tri, cow.crps.to_3d(s.tri, s.p));
    }
    EXPECT_GE(double(same) / double(n), 0.999);

    sim::TriangleMesh moved = cow.mesh;
    moved.positions[0].x += 0.005 * cow.mesh.bounds().diagonal();
    const mosaic::MosaicPattern elsewhere(g.cells, moved, "moved");
    EXPECT_NE(elsewhere.transfer(), nullptr);
}

// The other way round: a pattern grown on a refined copy of a low-poly mesh
// (sim/remesh/cell_scale_surface.h) rendered on the mesh itself. Each render triangle
// spans 64 simulation triangles; every point of it is carried to the same 3D point.
TEST(SurfaceTransfer, ACoarseMeshFindsItsRefinedCopyUnderEveryPoint) {
    const sim::TriangleMesh coarse = sim::load_mesh("procedural:icosphere:1");
    sim::TriangleMesh fine = coarse;
    for (int level = 0; level < 3; ++level)
        fine = sim::subdivide(fine, sim::Subdivision::midpoint);
    const sim::Surface simulation = sim::build_surface(fine);
    const sim::Surface render = sim::build_surface(coarse);
    const SurfaceTransfer transfer(simulation, render.mesh, "fine.cells", "coarse");
    size_t off = 0;
    double worst = 0;
    const auto points = sim::sample_surface_uniform(render.crps, 20000, 5);
    for (const auto &s : points) {
        const sim::Vec3d b = render.crps.to_barycentric(s.tri, s.p);
        const auto at = transfer.map(s.tri, float(b.y), float(b.z));
        const sim::Vec3d there = simulation.crps.to_3d(
            at.tri, simulation.crps.barycentric_to_2d(
                        at.tri, {1.0 - at.b1 - at.b2, double(at.b1), double(at.b2)}));
        const double d = length(there - render.crps.to_3d(s.tri, s.p));
        worst = std::max(worst, d);
        off += d > 1e-5;  // the sphere's diameter is 2
    }
    EXPECT_EQ(off, 0u) << "worst distance " << worst;
}

TEST(SurfaceTransfer, TheLoopSubdividedCowShowsThePatternAtItsClosestPoints) {
    Grown g;
    const sim::TriangleMesh smooth =
        sim::subdivide(g.on_cow->surface().mesh, sim::Subdivision::loop);
    const double a = g.agreement(smooth, "loop.obj", 4000, [&](sim::TriId, sim::Vec3d p) {
        return g.type_near(p);
    });
    EXPECT_GE(a, 0.995);
    std::printf("Loop-subdivided cow: %.4f of points show the cow's colour\n", a);
}

TEST(SurfaceTransfer, AScaledAndMovedCopyShowsTheSamePattern) {
    Grown g;
    sim::TriangleMesh big = g.on_cow->surface().mesh;
    for (sim::Vec3d &p : big.positions) p = p * 2.0 + sim::Vec3d{1, -0.5, 3};
    const double a = g.agreement(big, "big.obj", 20000, [&](sim::TriId t, sim::Vec3d p) {
        return g.type_on_cow(t, (p - sim::Vec3d{1, -0.5, 3}) * 0.5);
    });
    EXPECT_GE(a, 0.999);
}

TEST(SurfaceTransfer, AnotherShapeIsRefusedNamingBothFiles) {
    Grown g;
    const std::string bunny = test::sample_mesh("bunny00.off");
    try {
        const mosaic::MosaicPattern p(g.cells, bunny);
        ADD_FAILURE() << "the bunny was taken for the cow";
    } catch (const InputError &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(g.cells), std::string::npos) << what;
        EXPECT_NE(what.find(bunny), std::string::npos) << what;
        EXPECT_NE(what.find("another surface"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace pelage::pattern::transfer
