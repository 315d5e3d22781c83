// The simulation surface at the cells' scale (sim/remesh/cell_scale_surface.h) against
// the surface it stands for. The reference is the cow itself: the input is the cow split
// twice at its edge midpoints (the same surface with 16× the triangles), and distances
// are measured to the cow's own 5 804 triangles by brute force (Ericson's closest point),
// not through anything the simplification used.
#include "sim/remesh/cell_scale_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/subdivide.h"
#include "sim/remesh/simplify.h"
#include "tests/sim/remesh/surface_reference.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

using test::distance_to_mesh;
using test::euler_and_open_edges;

TEST(CellScaleSurface, LeavesALightMeshAlone) {
    // Teo's 760-triangle sphere with 150 cells: triangles smaller than the cells, but
    // few enough to unfold as they are.
    const TriangleMesh sphere = load_mesh("procedural:sphere:20x20");
    const double area = sphere.surface_area(), edge = mean_edge_length(sphere);
    CellScaleReport report =
        plan_cell_scale(sphere, {area, 150, 1.15 * 2 * std::sqrt(area / 150)});
    const TriangleMesh out = remesh_to_cell_scale(sphere, &report);
    EXPECT_GT(report.cell_spacing, edge);
    EXPECT_LT(report.neighbourhood_entries, max_neighbourhood_entries);
    EXPECT_FALSE(report.simplified);
    EXPECT_EQ(out.triangles, sphere.triangles);
}

TEST(CellScaleSurface, LeavesAMeshAtTheCellsScaleAlone) {
    const TriangleMesh cow = load_mesh(test::sample_mesh("cow.off"));
    const double area = cow.surface_area(), edge = mean_edge_length(cow);
    // Cells spaced 0.9 mean edges apart: triangles are not smaller than the cells.
    const double cells = area / (0.9 * edge * 0.9 * edge);
    // Even with neighbourhoods as wide as on the dense cow below.
    CellScaleReport report = plan_cell_scale(cow, {area, cells, 0.05});
    const TriangleMesh out = remesh_to_cell_scale(cow, &report);
    EXPECT_FALSE(report.simplified);
    EXPECT_EQ(out.positions, cow.positions);
    EXPECT_EQ(out.triangles, cow.triangles);
}

TEST(CellScaleSurface, ALowPolyAnimalIsRefinedToTheCellsScale) {
    // 80 triangles for 277 000 cells (the spider's abdomen in assimp's test models holds
    // 3 500 per triangle): split at the edge midpoints until at most 128 per triangle.
    const TriangleMesh coarse = load_mesh("procedural:icosphere:1");
    const double area = coarse.surface_area();
    CellScaleReport report =
        plan_cell_scale(coarse, {area, 277000, 1.15 * 2 * std::sqrt(area / 24000)});
    EXPECT_FALSE(report.simplified);
    EXPECT_EQ(report.refine_levels, 3);  // 3 462 -> 866 -> 216 -> 54 per triangle
    const TriangleMesh out = remesh_to_cell_scale(coarse, &report);
    EXPECT_EQ(out.num_triangles(), 80u * 64u);
    EXPECT_EQ(report.output_triangles, out.num_triangles());
    const double per_triangle = 277000.0 / double(out.num_triangles());
    EXPECT_LE(per_triangle, max_cells_per_triangle);
    EXPECT_GT(per_triangle, max_cells_per_triangle / 4);
    // The same surface: the same area, and every new vertex on the input's triangles.
    EXPECT_NEAR(out.surface_area(), area, 1e-12 * area);
}

TEST(CellScaleSurface, ADenseCowIsSimplifiedAndStaysOnTheCow) {
    const TriangleMesh cow = load_mesh(test::sample_mesh("cow.off"));
    const TriangleMesh dense =
        subdivide(subdivide(cow, Subdivision::midpoint), Subdivision::midpoint);
    // teo-leopard's counts and radius: 5 000 -> 8 474 cells, w_r 3.3.
    const double area = dense.surface_area(), cells = 8474;
    const double radius = 1.15 * 3.3 * std::sqrt(area / 5000);
    CellScaleReport report = plan_cell_scale(dense, {area, cells, radius});
    const TriangleMesh out = remesh_to_cell_scale(dense, &report);
    ASSERT_TRUE(report.simplified);
    EXPECT_EQ(report.input_triangles, dense.num_triangles());
    EXPECT_EQ(report.output_triangles, out.num_triangles());
    // At most about s²/(√3/4·s²) ≈ 2.3 triangles per cell (edges of s); the edge that
    // brings the neighbourhoods down to max_neighbourhood_entries is longer, and the
    // bound on the deviation keeps more triangles on the ears, horns and legs.
    EXPECT_GE(report.edge_length, report.cell_spacing);
    EXPECT_GE(report.min_edge_length, report.cell_spacing);
    EXPECT_LT(double(out.num_triangles()), 5.0 * cells);
    EXPECT_LT(out.num_triangles() * 4, dense.num_triangles());
    const double diagonal = cow.bounds().diagonal();
    EXPECT_LE(report.max_deviation, max_deviation_fraction * diagonal * (1 + 1e-12));

    // Every vertex of the result lies within the bound of the cow's surface.
    double worst_vertex = 0;
    for (const Vec3d &p : out.positions)
        worst_vertex = std::max(worst_vertex, distance_to_mesh(p, cow));
    EXPECT_LE(worst_vertex, report.max_deviation * (1 + 1e-9));

    // And the cow lies close to the result: area-uniform points of the cow, within a
    // quarter of the 2 % at which a render mesh counts as another shape.
    const Surface cow_surface = build_surface(cow);
    double worst_point = 0;
    for (const SurfacePointSample &s : sample_surface_uniform(cow_surface.crps, 2000, 7))
        worst_point = std::max(worst_point,
                               distance_to_mesh(cow_surface.crps.to_3d(s.tri, s.p), out));
    EXPECT_LE(worst_point, 0.005 * diagonal) << "of the diagonal " << diagonal;

    // Same topology (a closed surface of the same genus) and nearly the same area.
    EXPECT_EQ(euler_and_open_edges(out), euler_and_open_edges(dense));
    EXPECT_NEAR(out.surface_area() / area, 1.0, 0.02);
}

TEST(CellScaleSurface, NeighbourhoodsThatWouldNotFitAreRefusedSayingWhatToChange) {
    // bunny00 with giraffe-reticulata's start: 19 883 cells, w_r 4.5, triangles larger
    // than the final cells (so not simplified to them) but 35 M unfolded triangles: the
    // plan coarsens it, and with --surface input (or a coarsening that keeps no copy)
    // the input's neighbourhoods are what the memory check weighs.
    const TriangleMesh bunny = load_mesh(test::sample_mesh("bunny00.off"));
    const double area = bunny.surface_area();
    const double R = 1.15 * 4.5 * std::sqrt(area / 19883);
    CellScaleReport plan = plan_cell_scale(bunny, {area, 226662, R});
    ASSERT_TRUE(plan.coarsening);
    EXPECT_TRUE(plan.simplified);
    // By the estimate's own formula, checked by hand: triangles × π(R + e)² / (√3/4·e²).
    const double e = plan.input_mean_edge;
    EXPECT_GT(e, plan.cell_spacing);
    EXPECT_NEAR(plan.neighbourhood_entries,
                double(bunny.num_triangles()) * M_PI * (R + e) * (R + e) /
                    (std::sqrt(3.0) / 4 * e * e),
                1e-6 * plan.neighbourhood_entries);
    // The planned edge brings the same estimate, on the area tiled by triangles of that
    // edge, down to max_neighbourhood_entries.
    const double L = plan.edge_length, a = std::sqrt(3.0) / 4 * L * L;
    EXPECT_GT(L, e);
    EXPECT_NEAR(area / a * M_PI * (R + L) * (R + L) / a, max_neighbourhood_entries,
                1e-6 * max_neighbourhood_entries);
    EXPECT_NO_THROW(check_neighbourhood_memory(plan, 1e9, "bunny00.off"));

    plan.simplified = plan.coarsening = false;
    EXPECT_GT(neighbourhood_bytes(plan), 1e9);
    EXPECT_NO_THROW(check_neighbourhood_memory(plan, 16e9, "bunny00.off"));
    try {
        check_neighbourhood_memory(plan, 1e9, "bunny00.off");
        ADD_FAILURE() << "a 1 GB budget was accepted";
    } catch (const InputError &error) {
        EXPECT_EQ(error.file(), "bunny00.off");
        EXPECT_EQ(error.field(), "simulation.initial_cells");
        const std::string what = error.what();
        EXPECT_NE(what.find("more cells"), std::string::npos) << what;
        EXPECT_NE(what.find("GB"), std::string::npos) << what;
    }
}

TEST(CellScaleSurface, AFineAnimalIsCoarsenedAndTheInputStaysOnTheCopy) {
    // The camel (19 536 triangles) with giraffe-reticulata's start (11 690 -> 115 357
    // cells, w_r 4.5): 5 cells per triangle, 4.9 M unfolded triangles estimated.
    const TriangleMesh camel = load_mesh(test::sample_mesh("camel.off"));
    const double area = camel.surface_area();
    CellScaleReport plan =
        plan_cell_scale(camel, {area, 115357, 1.15 * 4.5 * std::sqrt(area / 11690)});
    ASSERT_TRUE(plan.coarsening);
    const TriangleMesh out = remesh_to_cell_scale(camel, &plan);
    ASSERT_TRUE(plan.simplified);
    EXPECT_EQ(plan.output_triangles, out.num_triangles());
    EXPECT_LT(out.num_triangles() * 2, camel.num_triangles());
    // Checked by brute force, not through CGAL's tree: every vertex of the copy lies
    // within the bound of the camel, and area-uniform points of the camel (not only its
    // vertices, which the coarsening checked) lie within the two-sided bound of the copy.
    const double diagonal = camel.bounds().diagonal();
    double worst_vertex = 0;
    for (const Vec3d &p : out.positions)
        worst_vertex = std::max(worst_vertex, distance_to_mesh(p, camel));
    EXPECT_LE(worst_vertex, plan.max_deviation * (1 + 1e-9));
    const Surface camel_surface = build_surface(camel);
    double worst_point = 0;
    for (const SurfacePointSample &s :
         sample_surface_uniform(camel_surface.crps, 2000, 3))
        worst_point = std::max(
            worst_point, distance_to_mesh(camel_surface.crps.to_3d(s.tri, s.p), out));
    EXPECT_LE(worst_point, max_input_distance_fraction * diagonal) << "of " << diagonal;
    EXPECT_LE(plan.max_input_distance, max_input_distance_fraction * diagonal);
    EXPECT_EQ(euler_and_open_edges(out), euler_and_open_edges(camel));
    EXPECT_NEAR(out.surface_area() / area, 1.0, max_area_change);
}

}  // namespace
}  // namespace pelage::sim
