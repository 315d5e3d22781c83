// Spot statistics (pattern/statistics/spot_statistics.h) against configurations whose
// answers are known in closed form: cells at the six vertices of an octahedron on a
// finely tessellated unit sphere tile it with six congruent spherical squares, each
// bounded by four great-circle arcs between cube-vertex directions, of angle acos(1/3).
#include "pattern/statistics/spot_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"
#include "sim/run/cells_data.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const std::string sphere = "procedural:icosphere:4";  // 5120 triangles, radius 1

// The surface point of the mesh in direction d (the triangle the ray from the centre
// crosses).
sim::SurfacePoint point_towards(const sim::Surface &s, sim::Vec3d d) {
    for (sim::TriId t = 0; t < s.crps.num_triangles(); ++t) {
        const sim::CrpsFrame &f = s.crps.frame(t);
        const double along = dot(f.normal, d);
        if (along <= 0) continue;
        // The plane holds every point p with dot(n, p) = dot(n, c) for its centroid c.
        const sim::Vec3d c = s.crps.to_3d(t, {0, 0});
        const sim::Vec3d p = d * (dot(f.normal, c) / along);
        const sim::Vec2d q = s.crps.to_2d(t, p);
        const sim::Vec3d b = sim::barycentric_in(f, q);
        if (b.x >= -1e-12 && b.y >= -1e-12 && b.z >= -1e-12) return {t, q};
    }
    ADD_FAILURE() << "no triangle towards the direction";
    return {};
}

// Writes a two-type .cells file with one cell per direction, of the given types
// (0 = F, 1 = B).
std::string write_cells(const TempDir &tmp, const std::vector<sim::Vec3d> &at,
                        const std::vector<uint8_t> &type) {
    const sim::Surface s = sim::build_surface(sphere);
    const sim::CellTypes types({sim::CellType{"F", {0.1f, 0.05f, 0.02f}},
                                sim::CellType{"B", {0.9f, 0.6f, 0.3f}}},
                               {{1, 0}, {0, 1}}, {{0.5, 0}, {0, 0.5}});
    sim::Cells cells(s.crps.num_triangles());
    for (size_t k = 0; k < at.size(); ++k) cells.add(point_towards(s, at[k]), type[k]);
    const std::string path = tmp.file("octahedron.cells");
    sim::write_cells_file(path,
                          sim::make_cells_data(s.mesh, s.crps, types, cells, "{}", 1));
    return path;
}

const std::vector<sim::Vec3d> octahedron = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},
                                            {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}};

TEST(SpotStatistics, TwoOppositeSquaresOnTheOctahedralTiling) {
    TempDir tmp;
    // F at the poles, B on the equator: two spots, one background ring.
    const std::string cells = write_cells(tmp, octahedron, {0, 0, 1, 1, 1, 1});
    const pattern::mosaic::MosaicPattern pattern(cells, sphere);
    const auto s = pattern::statistics::measure_spot_statistics(pattern, 40);
    ASSERT_EQ(s.by_type.size(), 2u);
    EXPECT_NEAR(s.by_type[0], 1.0 / 3.0, 0.003);
    EXPECT_EQ(s.spots, 2u);
    EXPECT_NEAR(s.spot_area_mean, s.area / 6, 0.003 * s.area);
    EXPECT_NEAR(s.spot_area_sd, 0, 0.003 * s.area);
    // A spherical square: area 4 pi / 6, perimeter 4 acos(1/3) (areas are taken
    // relative to the polyhedron's, whose chords shorten the arcs by under 1 %). The
    // traced border is measured within 0.3 % of the arcs; circularity goes with 1 / P^2,
    // so within 1.5 % of the perimeter it lies in [1 / 1.015², 1 / 0.985²] of the truth.
    const double perimeter = 4 * std::acos(1.0 / 3.0);
    const double circularity =
        4 * std::numbers::pi * (s.area / 6) / (perimeter * perimeter);
    ASSERT_EQ(s.spot_perimeters.size(), 2u);
    EXPECT_NEAR(s.spot_perimeters[0], perimeter, 0.015 * perimeter);
    EXPECT_NEAR(s.spot_perimeters[1], perimeter, 0.015 * perimeter);
    EXPECT_GE(s.spot_circularity_mean, circularity / (1.015 * 1.015));
    EXPECT_LE(s.spot_circularity_mean, circularity / (0.985 * 0.985));
    EXPECT_NEAR(s.spot_complexity, 1 - s.spot_circularity_mean, 1e-12);  // equal areas
    EXPECT_DOUBLE_EQ(s.spot_neighbours_mean, 1.0);  // the two squares face each other
    EXPECT_EQ(s.background_components, 1u);
    EXPECT_DOUBLE_EQ(s.background_largest_share, 1.0);
    EXPECT_DOUBLE_EQ(s.background_near_spot, 1.0);
}

TEST(SpotStatistics, AdjacentSpotCellsMakeOneSpotAndSeparatedBackgroundSplits) {
    TempDir tmp;
    // F at +z, -z, +x, -x joins into one band through the equator's ±x squares; B at
    // +y and -y are two background islands, each touching the band.
    const std::string cells = write_cells(tmp, octahedron, {0, 0, 0, 0, 1, 1});
    const pattern::mosaic::MosaicPattern pattern(cells, sphere);
    const auto s = pattern::statistics::measure_spot_statistics(pattern, 40);
    EXPECT_EQ(s.spots, 1u);
    EXPECT_NEAR(s.by_type[0], 2.0 / 3.0, 0.003);
    EXPECT_NEAR(s.spot_area_mean, s.area * 2 / 3, 0.003 * s.area);
    EXPECT_DOUBLE_EQ(s.spot_neighbours_mean, 0.0);
    EXPECT_EQ(s.background_components, 2u);
    EXPECT_NEAR(s.background_largest_share, 0.5, 0.01);
    EXPECT_DOUBLE_EQ(s.background_near_spot, 1.0);
    // Its border is the two islands' borders: 8 arcs; circularity 4 pi (2A/3) / P^2.
    const double perimeter = 8 * std::acos(1.0 / 3.0);
    const double circularity =
        4 * std::numbers::pi * (s.area * 2 / 3) / (perimeter * perimeter);
    EXPECT_NEAR(s.spot_perimeters.at(0), perimeter, 0.015 * perimeter);
    EXPECT_GE(s.spot_circularity_mean, circularity / (1.015 * 1.015));
    EXPECT_LE(s.spot_circularity_mean, circularity / (0.985 * 0.985));
}

TEST(SpotStatistics, CoarserGridsAgreeOnASimulatedMosaic) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 1200, 0.3, 4);
    const pattern::mosaic::MosaicPattern pattern(cells, mesh);
    const auto fine = pattern::statistics::measure_spot_statistics(pattern, 12);
    const auto coarse = pattern::statistics::measure_spot_statistics(pattern, 6);
    EXPECT_NEAR(fine.by_type[0], coarse.by_type[0], 0.01);
    EXPECT_NEAR(double(coarse.spots), double(fine.spots), 0.05 * double(fine.spots));
    EXPECT_NEAR(coarse.spot_complexity, fine.spot_complexity, 0.05);
    // Deterministic at any thread count: the look-ups are written to fixed slots.
    const auto again = pattern::statistics::measure_spot_statistics(pattern, 6);
    EXPECT_EQ(again.spot_areas, coarse.spot_areas);
    EXPECT_EQ(again.spot_perimeters, coarse.spot_perimeters);
}

}  // namespace
}  // namespace pelage::test
