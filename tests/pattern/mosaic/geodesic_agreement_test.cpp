// The surface-distance core against an independent reference: CGAL's exact polyhedral
// geodesics (tests/oracle). Window propagation (sim/geodesic) must give the oracle's
// distances; the closest-cell index must name the geodesically nearest cell, give it
// the right colour, never report a distance shorter than the straight line to the cell
// it returns (no path on the surface is), and report that cell's distance within 1 %.
// On the sample meshes, with 20 000 random cells.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pattern/mosaic/closest_cell.h"
#include "pattern/mosaic/pattern.h"
#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/geodesic/window_propagation.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/oracle/exact_geodesic_oracle.h"
#include "tests/test_paths.h"

namespace pelage::pattern::mosaic {
namespace {

test::SurfaceLocation location(const sim::Crps &crps, sim::TriId t, sim::Vec2d p) {
    const sim::Vec3d b = crps.to_barycentric(t, p);
    return {t, b.y, b.z};
}

class GeodesicAgreement : public ::testing::TestWithParam<const char *> {};

TEST_P(GeodesicAgreement, WindowPropagationGivesTheExactDistances) {
    const sim::Surface s = sim::build_surface(test::sample_mesh(GetParam()));
    const test::ExactGeodesicOracle oracle(s.mesh);
    const sim::GeodesicMesh mesh(s.crps);
    sim::WindowPropagation prop(mesh);
    std::vector<sim::GeodesicWindow> windows;
    const double radius = 0.15 * s.mesh.bounds().diagonal();
    const auto sources = sim::sample_surface_uniform(s.crps, 3, 41);
    const auto targets = sim::sample_surface_uniform(s.crps, 3000, 42);
    std::vector<test::SurfaceLocation> at;
    for (const auto &q : targets) at.push_back(location(s.crps, q.tri, q.p));
    size_t compared = 0, off = 0;
    double worst = 0;
    for (const auto &src : sources) {
        prop.run(src.tri, src.p, radius, windows);
        std::vector<std::vector<sim::GeodesicWindow>> by_face(s.mesh.num_triangles());
        for (const auto &w : windows) by_face[w.face].push_back(w);
        const std::vector<double> exact =
            oracle.distances(location(s.crps, src.tri, src.p), at);
        for (size_t i = 0; i < targets.size(); ++i) {
            if (!(exact[i] < 0.9 * radius)) continue;
            const auto &ws = by_face[targets[i].tri];
            const double d = sim::distance_from_windows(ws.data(), ws.data() + ws.size(),
                                                        targets[i].p);
            ++compared;
            const double err = std::abs(d - exact[i]) / exact[i];
            worst = std::max(worst, err);
            off += err > 1e-6;
        }
    }
    EXPECT_GT(compared, 300u);
    EXPECT_EQ(off, 0u) << "worst relative error " << worst;
}

TEST_P(GeodesicAgreement, ClosestCellIsTheGeodesicallyNearest) {
    const sim::Surface s = sim::build_surface(test::sample_mesh(GetParam()));
    const test::ExactGeodesicOracle oracle(s.mesh);
    std::vector<CellOnSurface> list;
    std::vector<test::SurfaceLocation> sources;
    uint32_t id = 0;
    for (const auto &p : sim::sample_surface_uniform(s.crps, 20000, 43)) {
        list.push_back({p.tri, p.p.x, p.p.y, id, uint8_t(id % 2)});
        ++id;
    }
    const CellTable cells = make_cell_table(s.crps.num_triangles(), list);
    for (sim::TriId t = 0; t < cells.num_triangles(); ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
            sources.push_back(location(s.crps, t, {cells.x[k], cells.z[k]}));
    const ClosestCellIndex index(s.crps, cells);
    const auto queries = sim::sample_surface_uniform(s.crps, 5000, 44);
    std::vector<test::SurfaceLocation> at;
    for (const auto &q : queries) at.push_back(location(s.crps, q.tri, q.p));
    const auto exact = oracle.nearest(sources, at);
    size_t same = 0, same_colour = 0, impossible = 0, far = 0;
    for (size_t i = 0; i < queries.size(); ++i) {
        const auto &q = queries[i];
        const ClosestCell c =
            index.find_nearest(q.tri, Vec2f{float(q.p.x), float(q.p.y)});
        ASSERT_NE(c.index, ClosestCell::none);
        same += c.index == exact[i].source;
        same_colour += cells.type[c.index] == cells.type[exact[i].source];
        const sim::Vec3d p = s.crps.to_3d(q.tri, q.p);
        const sim::Vec3d cell =
            s.crps.to_3d(sim::TriId(sources[c.index].tri),
                         {double(cells.x[c.index]), double(cells.z[c.index])});
        impossible += c.f1 < length(p - cell) * (1 - 1e-5);
        // The returned cell's exact distance: the oracle's when it is the nearest.
        double d = exact[i].distance;
        if (c.index != exact[i].source)
            d = oracle.distances(sources[c.index], {&at[i], 1})[0];
        far += std::abs(c.f1 - d) > 0.01 * d;
    }
    const double n = double(queries.size());
    EXPECT_GE(same / n, 0.995);
    EXPECT_GE(same_colour / n, 0.999);
    EXPECT_EQ(impossible, 0u);
    EXPECT_EQ(far, 0u);
    RecordProperty("same_cell", std::to_string(same / n));
    RecordProperty("same_colour", std::to_string(same_colour / n));
    std::printf(
        "%s: same cell %.4f, same colour %.4f, impossible %zu, off by > 1 %% %zu\n",
        GetParam(), same / n, same_colour / n, impossible, far);
}

// Simulated mosaics as `pelage sim` grows them (the cells crowd and clump, unlike random
// ones), looked up through the renderer's MosaicPattern.
TEST(GeodesicAgreementPresets, SimulatedPatternsOnTheSampleAnimals) {
    test::TempDir tmp;
    const std::pair<const char *, const char *> runs[] = {{"cow.off", "walter-cheetah"},
                                                          {"bull.off", "teo-jaguar"}};
    for (const auto &[mesh, preset] : runs) {
        const std::string cells_path = tmp.file(std::string(preset) + ".cells");
        ASSERT_EQ(test::run_pelage("sim --mesh " + test::sample_mesh(mesh) +
                                   " --preset " + preset + " --seed 7 -o " + cells_path),
                  0);
        const MosaicPattern pattern(cells_path, test::sample_mesh(mesh));
        const sim::Surface &s = pattern.surface();
        const CellTable &cells = pattern.cells();
        const test::ExactGeodesicOracle oracle(s.mesh);
        std::vector<test::SurfaceLocation> sources;
        for (sim::TriId t = 0; t < cells.num_triangles(); ++t)
            for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
                sources.push_back(location(s.crps, t, {cells.x[k], cells.z[k]}));
        const auto queries = sim::sample_surface_uniform(s.crps, 4000, 45);
        std::vector<test::SurfaceLocation> at;
        for (const auto &q : queries) at.push_back(location(s.crps, q.tri, q.p));
        const auto exact = oracle.nearest(sources, at);
        size_t same = 0, same_colour = 0, far = 0;
        for (size_t i = 0; i < queries.size(); ++i) {
            const auto &q = queries[i];
            const ClosestCell c =
                pattern.index().find_nearest(q.tri, Vec2f{float(q.p.x), float(q.p.y)});
            ASSERT_NE(c.index, ClosestCell::none);
            same += c.index == exact[i].source;
            same_colour += cells.type[c.index] == cells.type[exact[i].source];
            double d = exact[i].distance;
            if (c.index != exact[i].source)
                d = oracle.distances(sources[c.index], {&at[i], 1})[0];
            far += std::abs(c.f1 - d) > 0.01 * d;
        }
        const double n = double(queries.size());
        EXPECT_GE(same / n, 0.995) << preset;
        EXPECT_GE(same_colour / n, 0.999) << preset;
        EXPECT_EQ(far, 0u) << preset;
        std::printf("%s on %s: same cell %.4f, same colour %.4f\n", preset, mesh,
                    same / n, same_colour / n);
    }
}

// A shipped preset on the sample cow, with the seed whose index once grew past 22 GB:
// a least-squares position of a path bent round a vertex ran off metres from its
// centimetre-sized region, and the reach it implied sent every cell's windows across the
// whole cow. The reach stays within a few cell spacings.
TEST(GeodesicAgreementPresets, TheIndexReachesAFewCellSpacingsOnAShippedPreset) {
    test::TempDir tmp;
    const std::string cells_path = tmp.file("tippelskirchi.cells");
    ASSERT_EQ(
        test::run_pelage("sim --mesh " + test::sample_mesh("cow.off") +
                         " --preset giraffe-tippelskirchi --seed 2 -q -o " + cells_path),
        0);
    const MosaicPattern pattern(cells_path, test::sample_mesh("cow.off"));
    const ClosestCellStats &stats = pattern.index().stats();
    EXPECT_LE(stats.geodesic_radius, 10 * pattern.index().spacing());
    EXPECT_LT(double(stats.geodesic_work) / double(pattern.cells().size()), 1000)
        << "windows settled per cell";
}

// A surface of separate parts, as real files are (an animal, its eyes, props): a body
// with many cells, an eye with two, a horn with none, each a fraction of a cell spacing
// from the body in space. No path leaves a part, so each part's points find the
// geodesically nearest of that part's cells, as the oracle says, and the horn's find
// none; and the parts without three cells do not send the body's cells across the
// whole surface looking for more.
TEST(GeodesicAgreementParts, EachPartFindsItsOwnNearestCell) {
    sim::TriangleMesh mesh;
    auto add = [&mesh](const sim::TriangleMesh &part, sim::Vec3d offset) {
        const auto base = static_cast<sim::VertId>(mesh.positions.size());
        for (const sim::Vec3d &p : part.positions) mesh.positions.push_back(p + offset);
        for (const auto &t : part.triangles)
            mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    };
    add(sim::make_icosphere(3, 1.0), {0, 0, 0});
    add(sim::make_icosphere(2, 0.1), {1.11, 0, 0});  // the eye
    add(sim::make_icosphere(2, 0.1), {0, 1.11, 0});  // the horn
    const sim::Surface s = sim::build_surface(mesh);
    enum Part { body, eye, horn };
    auto part_of = [&s](sim::TriId t) {
        const sim::Vec3d c = s.crps.to_3d(t, {0, 0});
        return length(c) < 1.005 ? body : (c.x > 0.5 ? eye : horn);
    };
    std::vector<CellOnSurface> placed;
    for (const auto &q : sim::sample_surface_uniform(s.crps, 3000, 3))
        if (part_of(q.tri) == body)
            placed.push_back({q.tri, q.p.x, q.p.y, uint32_t(placed.size()), 0});
    const size_t on_body = placed.size();
    for (const auto &q : sim::sample_surface_uniform(s.crps, 20000, 4))
        if (part_of(q.tri) == eye && placed.size() < on_body + 2)
            placed.push_back({q.tri, q.p.x, q.p.y, uint32_t(placed.size()), 1});
    ASSERT_EQ(placed.size(), on_body + 2);
    const CellTable cells = make_cell_table(s.crps.num_triangles(), placed);
    const ClosestCellIndex index(s.crps, cells);

    std::vector<test::SurfaceLocation> sources;
    for (sim::TriId t = 0; t < cells.num_triangles(); ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
            sources.push_back(location(s.crps, t, {cells.x[k], cells.z[k]}));
    const test::ExactGeodesicOracle oracle(s.mesh);
    // Every point that falls on the small parts, and the first 3 000 on the body.
    std::vector<sim::SurfacePointSample> queries;
    size_t body_queries = 0;
    for (const auto &q : sim::sample_surface_uniform(s.crps, 40000, 5))
        if (part_of(q.tri) != body || body_queries++ < 3000) queries.push_back(q);
    std::vector<test::SurfaceLocation> at;
    for (const auto &q : queries) at.push_back(location(s.crps, q.tri, q.p));
    const auto exact = oracle.nearest(sources, at);
    size_t asked[3] = {0, 0, 0}, same[3] = {0, 0, 0};
    for (size_t i = 0; i < queries.size(); ++i) {
        const auto &q = queries[i];
        const Part part = part_of(q.tri);
        const ClosestCell c =
            index.find_nearest(q.tri, Vec2f{float(q.p.x), float(q.p.y)});
        ++asked[part];
        if (part == horn)
            same[part] += c.index == ClosestCell::none;
        else
            same[part] += c.index == exact[i].source;
    }
    ASSERT_GT(asked[eye], 200u);
    ASSERT_GT(asked[horn], 200u);
    EXPECT_GE(same[body], 0.995 * asked[body]);
    EXPECT_GE(same[eye], 0.99 * asked[eye]);
    EXPECT_EQ(same[horn], asked[horn]);
    // Every cell's windows over the whole body would settle over 10^4 windows per cell;
    // its own neighbourhood takes a few hundred.
    const double work = double(index.stats().geodesic_work) / double(cells.size());
    EXPECT_LT(work, 1000) << "windows settled per cell";
    std::printf(
        "body %zu/%zu, eye %zu/%zu, horn %zu/%zu; %.0f windows settled per cell\n",
        same[body], asked[body], same[eye], asked[eye], same[horn], asked[horn], work);
}

INSTANTIATE_TEST_SUITE_P(SampleMeshes, GeodesicAgreement,
                         ::testing::Values("cow.off", "bull.off", "camel.off",
                                           "triceratops.off", "elephant.off"),
                         [](const auto &info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace pelage::pattern::mosaic
