// The clonal mosaic's coarse level of detail (pattern/mosaic/mosaic_lod.h): each
// triangle's mean look is the area mean of the exact pattern over it; vertices carry the
// area-weighted mean of their triangles', interpolated continuously across edges; the
// blend weight ramps from 0 at one triangle size to 1 at two.
#include "pattern/mosaic/mosaic_lod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const std::string mesh_spec = "procedural:icosphere:2";  // 320 triangles

pattern::mosaic::FilteredLook type_look(const pattern::mosaic::MosaicPattern &p,
                                        uint32_t cell) {
    const sim::CellsFileType &t = p.types()[p.cells().type[cell]];
    return {{t.colour[0], t.colour[1], t.colour[2], t.eumelanin, t.pheomelanin}};
}

struct Fixture {
    TempDir tmp;
    std::string cells = simulate_two_type_cells(tmp, mesh_spec, 1500);
    pattern::mosaic::MosaicPattern pattern{cells, mesh_spec};
    pattern::mosaic::MosaicLod lod{
        pattern, [this](uint32_t c) { return type_look(pattern, c); }, 2};
};

// The mean over a triangle, against 4000 random area-uniform points of the exact pattern:
// the grid of sub-triangle centres the level is built from is off by a fraction of the
// colour step only where a boundary crosses a sub-triangle.
TEST(MosaicLod, TriangleMeansAreTheAreaMeansOfThePattern) {
    Fixture f;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    double sum_error = 0, max_error = 0;
    int mixed = 0;  // triangles with both types in them
    const size_t nt = f.pattern.num_triangles();
    for (sim::TriId t = 0; t < nt; ++t) {
        double mean[5] = {0, 0, 0, 0, 0};
        const int n = 4000;
        for (int k = 0; k < n; ++k) {
            float b1 = u(rng), b2 = u(rng);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            const pattern::mosaic::ClosestCell c =
                f.pattern.index().find_nearest(t, b1, b2);
            ASSERT_NE(c.index, pattern::mosaic::ClosestCell::none);
            const pattern::mosaic::FilteredLook l = type_look(f.pattern, c.index);
            for (int ch = 0; ch < 5; ++ch) mean[ch] += l.v[ch] / n;
        }
        // Red: F is 0.1, B 0.9.
        if (mean[0] > 0.15 && mean[0] < 0.85) ++mixed;
        for (int ch = 0; ch < 5; ++ch) {
            const double e = std::abs(f.lod.triangle_mean(t).v[ch] - mean[ch]);
            sum_error += e / 5;
            max_error = std::max(max_error, e);
        }
    }
    EXPECT_GT(mixed,
              int(nt / 5));  // the test sees boundaries, not only uniform triangles
    EXPECT_LT(sum_error / double(nt), 0.01);
    EXPECT_LT(max_error, 0.1);
}

// Corners: the area-weighted mean of the triangles at the vertex, so the filtered look
// is the same from either side of an edge (continuous), and inside a triangle the
// barycentric interpolation of its corners.
TEST(MosaicLod, VertexMeansAreContinuousAcrossEdges) {
    Fixture f;
    const sim::TriangleMesh &mesh = f.pattern.surface().mesh;
    const sim::Crps &crps = f.pattern.surface().crps;
    // Reference corner values from the triangle means.
    std::vector<double> corner(5 * mesh.num_vertices(), 0.0),
        area(mesh.num_vertices(), 0.0);
    for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
        for (sim::VertId v : mesh.triangles[t]) {
            area[v] += crps.frame(t).area;
            for (int ch = 0; ch < 5; ++ch)
                corner[5 * v + ch] += crps.frame(t).area * f.lod.triangle_mean(t).v[ch];
        }
    const float corners_b[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const sim::VertId v = mesh.triangles[t][c];
            const pattern::mosaic::FilteredLook at =
                f.lod.at(t, corners_b[c][0], corners_b[c][1]);
            for (int ch = 0; ch < 5; ++ch)
                ASSERT_NEAR(at.v[ch], corner[5 * v + ch] / area[v], 1e-5)
                    << t << " " << c;
        }
    // The middle of every edge, seen from both of its triangles.
    const sim::Topology &topo = crps.topology();
    size_t edges = 0;
    for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
        for (sim::TriId n : topo.primary_neighbours(t)) {
            // The two shared vertices, as corners of t and of n.
            float bt[2] = {0, 0}, bn[2] = {0, 0};
            int shared = 0;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    if (mesh.triangles[t][a] == mesh.triangles[n][b]) {
                        ++shared;
                        if (a > 0) bt[a - 1] += 0.5f;
                        if (b > 0) bn[b - 1] += 0.5f;
                    }
            ASSERT_EQ(shared, 2);
            const pattern::mosaic::FilteredLook x = f.lod.at(t, bt[0], bt[1]),
                                                y = f.lod.at(n, bn[0], bn[1]);
            for (int ch = 0; ch < 5; ++ch) ASSERT_NEAR(x.v[ch], y.v[ch], 1e-5);
            ++edges;
        }
    EXPECT_EQ(edges, 3 * mesh.num_triangles());
}

TEST(MosaicLod, WeightRampsFromOneTriangleSizeToTwo) {
    Fixture f;
    const sim::CrpsFrame &fr = f.pattern.surface().crps.frame(7);
    double size = 0;
    for (int c = 0; c < 3; ++c) {
        const sim::Vec2d e = fr.v[(c + 1) % 3] - fr.v[c];
        size = std::max(size, std::sqrt(e.x * e.x + e.y * e.y));
    }
    EXPECT_EQ(f.lod.weight(7, 0.0f), 0.0f);
    EXPECT_EQ(f.lod.weight(7, float(0.99 * size)), 0.0f);
    EXPECT_NEAR(f.lod.weight(7, float(1.5 * size)), 0.5f, 1e-5);
    EXPECT_EQ(f.lod.weight(7, float(2.01 * size)), 1.0f);
    EXPECT_EQ(f.lod.weight(7, 1e30f), 1.0f);
    EXPECT_EQ(f.lod.weight(7, std::nanf("")), 0.0f);  // a bad footprint filters nothing
}

}  // namespace
}  // namespace pelage::test
