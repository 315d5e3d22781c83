// A triangle soup (tests/pattern/transfer/triangle_soup.h) rendered with the pattern
// grown on it (cell_cover.h): pieces too small to hold a cell show the cells of the
// closest piece that holds some, so no point of the mesh is without a cell. The
// references are brute force: which pieces hold cells, from the .cells file's cells
// per triangle and the soup's own piece numbers; the closest cell-bearing point of each
// sample, over every cell-bearing triangle.
#include "pattern/transfer/cell_cover.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "pattern/mosaic/pattern.h"
#include "sim/crps/surface.h"
#include "sim/mesh/closest_point.h"
#include "sim/mesh/mesh_load.h"
#include "tests/pattern/transfer/triangle_soup.h"
#include "tests/test_paths.h"

namespace pelage::pattern::transfer {
namespace {

// The soup written to a file and a small two-type pattern grown on it as is (no
// remeshing: the pattern's triangles are the soup's).
struct GrownSoup {
    test::TempDir tmp;
    test::TriangleSoup soup;
    std::string mesh, cells;
    GrownSoup(double offset, double separation) {
        soup = test::make_triangle_soup(sim::load_mesh("procedural:icosphere:3"), offset,
                                        separation, 57);
        mesh = tmp.file("soup.off");
        test::write_off_exact(mesh, soup.mesh);
        const std::string preset = test::two_type_preset(tmp, 300);
        cells = tmp.file("soup.cells");
        std::string err;
        EXPECT_EQ(test::run_pelage("sim --mesh " + mesh + " --preset " + preset + " -o " +
                                       cells + " --seed 2 --surface input",
                                   nullptr, &err),
                  0)
            << err;
    }
    // Per piece: whether any of its triangles holds a cell in the file.
    std::vector<char> pieces_with_cells(const sim::CellsData &data) const {
        std::vector<char> has(soup.pieces, 0);
        for (sim::TriId t = 0; t < data.num_triangles(); ++t)
            if (data.cell_row[t + 1] > data.cell_row[t]) has[soup.piece[t]] = 1;
        return has;
    }
};

sim::Vec3d point_of(const sim::Crps &crps, sim::TriId t, float b1, float b2) {
    return crps.to_3d(t,
                      crps.barycentric_to_2d(t, {1.0 - b1 - b2, double(b1), double(b2)}));
}

// Pieces offset by 2e-3 of the diagonal (pieces sharing a vertex at least 1.5e-3
// apart, beyond the stitch's 1e-3): the loader keeps every piece apart, as on the store
// meshes with thousands of components.
TEST(CellCover, EveryPointOfASoupFindsACellNearItsClosestCellBearingPoint) {
    GrownSoup g(2e-3, 1.5e-3);
    const mosaic::MosaicPattern pattern(g.cells, g.mesh);
    ASSERT_EQ(pattern.transfer(), nullptr) << "the pattern was grown on another surface";
    ASSERT_EQ(pattern.num_triangles(), g.soup.mesh.num_triangles())
        << "the loader joined or dropped triangles of the soup";
    const sim::Surface &s = pattern.surface();
    const std::vector<char> has = g.pieces_with_cells(pattern.data());

    // The reference report: pieces, triangles and area without a cell of their own.
    size_t without_triangles = 0, without_pieces = 0, missed_before = 0;
    double area = 0, without_area = 0, longest_edge = 0;
    for (size_t p = 0; p < g.soup.pieces; ++p) without_pieces += !has[p];
    for (sim::TriId t = 0; t < s.mesh.num_triangles(); ++t) {
        const double a = s.mesh.triangle_area(t);
        area += a;
        for (int k = 0; k < 3; ++k)
            longest_edge = std::max(longest_edge, length(s.mesh.vertex(t, k) -
                                                         s.mesh.vertex(t, (k + 1) % 3)));
        if (has[g.soup.piece[t]]) continue;
        without_area += a;
        ++without_triangles;
        // What a render found there before: no cell at all.
        missed_before += pattern.index().find_nearest(t, 1 / 3.0f, 1 / 3.0f).index ==
                         mosaic::ClosestCell::none;
    }
    ASSERT_GT(without_pieces, 100u) << "the soup's pieces are not smaller than the cells";
    EXPECT_EQ(missed_before, without_triangles);

    const CellCoverReport &r = pattern.cover().report();
    EXPECT_TRUE(pattern.cover().active());
    EXPECT_EQ(r.pieces, g.soup.pieces);
    EXPECT_EQ(r.carried_pieces, without_pieces);
    EXPECT_EQ(r.carried_triangles, without_triangles);
    EXPECT_NEAR(r.carried_area_share, without_area / area, 1e-9);
    EXPECT_EQ(r.without_cell_share, 0);
    std::printf("soup: %zu pieces, %zu without cells (%.2f %% of the area)\n",
                g.soup.pieces, without_pieces, 100 * without_area / area);

    const float samples[4][2] = {
        {1 / 3.0f, 1 / 3.0f}, {0.1f, 0.1f}, {0.8f, 0.1f}, {0.1f, 0.8f}};
    size_t missing = 0, far = 0, moved_with_cells = 0, cell_off = 0;
    for (sim::TriId t = 0; t < s.mesh.num_triangles(); ++t)
        for (const auto &b : samples) {
            const SurfaceTransfer::Target at = pattern.locate(t, b[0], b[1]);
            const mosaic::ClosestCell c =
                pattern.index().find_nearest(at.tri, at.b1, at.b2);
            if (c.index == mosaic::ClosestCell::none) {
                ++missing;
                continue;
            }
            const sim::Vec3d x = point_of(s.crps, at.tri, at.b1, at.b2);
            // The cell lies within its surface distance of the point it colours.
            const mosaic::CellTable &cells = pattern.cells();
            const auto row =
                std::upper_bound(cells.row.begin(), cells.row.end(), c.index);
            const sim::TriId cell_tri = sim::TriId(row - cells.row.begin() - 1);
            const sim::Vec3d centre =
                s.crps.to_3d(cell_tri, {cells.x[c.index], cells.z[c.index]});
            cell_off += length(centre - x) > c.f1 * (1 + 1e-4) + 1e-6;
            if (has[g.soup.piece[t]]) {
                // A piece with cells keeps its own lookups, untouched.
                moved_with_cells += at.tri != t || at.b1 != b[0] || at.b2 != b[1];
                continue;
            }
            // Brute force: the closest point of every cell-bearing triangle.
            const sim::Vec3d p = point_of(s.crps, t, b[0], b[1]);
            double nearest = std::numeric_limits<double>::infinity();
            for (sim::TriId u = 0; u < s.mesh.num_triangles(); ++u)
                if (has[g.soup.piece[u]])
                    nearest = std::min(
                        nearest, length(sim::closest_point_on_triangle(
                                            p, s.mesh.vertex(u, 0), s.mesh.vertex(u, 1),
                                            s.mesh.vertex(u, 2)) -
                                        p));
            // Within a triangle's size of the closest cell-bearing point (the point of
            // a piece over a hole of pieces without cells lands on the hole's rim).
            far += length(x - p) > nearest + longest_edge;
        }
    EXPECT_EQ(missing, 0u) << "points without a cell";
    EXPECT_EQ(far, 0u) << "points carried away from the closest cell-bearing surface";
    EXPECT_EQ(moved_with_cells, 0u);
    EXPECT_EQ(cell_off, 0u);
}

// Copies within the weld (2e-6 of the diagonal): the loader stitches the pieces back
// into one sphere; the tiny pieces off it stay apart and are carried onto it.
TEST(CellCover, ASoupWhoseCopiesLieWithinTheWeldIsStitched) {
    GrownSoup g(2e-6, 0);
    sim::MeshLoadReport load;
    const sim::TriangleMesh welded = sim::load_mesh(g.mesh, &load);
    EXPECT_GT(load.clean.vertices_welded, 0u);
    ASSERT_EQ(welded.num_triangles(), g.soup.mesh.num_triangles());
    const sim::Surface s = sim::build_surface(welded);
    EXPECT_EQ(s.crps.topology().num_components, 1 + g.soup.floating);

    const mosaic::MosaicPattern pattern(g.cells, g.mesh);
    ASSERT_EQ(pattern.transfer(), nullptr);
    const std::vector<char> has = g.pieces_with_cells(pattern.data());
    size_t floating_without = 0;
    for (size_t p = g.soup.pieces - g.soup.floating; p < g.soup.pieces; ++p)
        floating_without += !has[p];
    EXPECT_EQ(pattern.cover().report().carried_pieces, floating_without);
    EXPECT_EQ(pattern.cover().report().pieces, 1 + g.soup.floating);
    size_t missing = 0;
    for (sim::TriId t = 0; t < pattern.num_triangles(); ++t) {
        const SurfaceTransfer::Target at = pattern.locate(t, 1 / 3.0f, 1 / 3.0f);
        missing += pattern.index().find_nearest(at.tri, at.b1, at.b2).index ==
                   mosaic::ClosestCell::none;
    }
    EXPECT_EQ(missing, 0u);

    // What `pelage crps` tells a user about the file.
    const std::string json = g.tmp.file("crps.json");
    ASSERT_EQ(test::run_pelage("crps --mesh " + g.mesh + " --stats-json " + json), 0);
    const auto stats = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(stats["components"].get<size_t>(), 1 + g.soup.floating);
    EXPECT_GT(stats["vertices_welded"].get<size_t>(), 0u);
}

// Pieces offset by 1e-4 of the diagonal (ten times the weld, pieces sharing a vertex at
// least 3e-5 apart): their boundaries are stitched (mesh_clean.h stitch_relative), so
// the pattern grows across them as on one surface and no piece borrows cells.
TEST(CellCover, ASoupSlightlyApartIsStitchedAlongItsCuts) {
    GrownSoup g(1e-4, 3e-5);
    sim::MeshLoadReport load;
    const sim::TriangleMesh stitched = sim::load_mesh(g.mesh, &load);
    EXPECT_EQ(load.clean.vertices_welded, 0u);  // every copy is beyond the weld
    EXPECT_GT(load.clean.vertices_stitched, 0u);
    ASSERT_EQ(stitched.num_triangles(), g.soup.mesh.num_triangles());  // none collapsed
    const sim::Surface s = sim::build_surface(stitched);
    EXPECT_EQ(s.crps.topology().num_components, 1 + g.soup.floating);
    // The source sphere is closed: stitched, only the floating triangles' edges (one
    // triangle each) are open, and no edge is shared by three.
    EXPECT_EQ(s.crps.topology().boundary_edges, 3 * g.soup.floating);
    EXPECT_EQ(s.crps.topology().nonmanifold_edges, 0u);
}

// A surface with no cells anywhere carries nothing: every point reports none, and the
// whole area is reported without a cell.
TEST(CellCover, ASurfaceWithoutCellsIsReportedWhole) {
    const sim::Surface s = sim::build_surface("procedural:icosphere:1");
    const CellCover cover(s, std::vector<char>(s.mesh.num_triangles(), 0));
    EXPECT_FALSE(cover.active());
    EXPECT_FALSE(cover.carries(0));
    EXPECT_NEAR(cover.report().without_cell_share, 1.0, 1e-12);
    EXPECT_EQ(cover.report().carried_triangles, 0u);
}

}  // namespace
}  // namespace pelage::pattern::transfer
