// The neighbours that push a cell in the relaxation against CGAL's exact polyhedral
// geodesics (tests/oracle): every pair the relaxation uses must be as far apart on the
// surface as it says, and every cell within r on the surface must push. Cells are
// area-uniform at teo-leopard's final density (8 474 cells, w_r 3.3) on animals whose
// horns, ears and legs fold planar unfoldings over.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/mosaic/cells.h"
#include "sim/mosaic/relaxation.h"
#include "tests/oracle/exact_geodesic_oracle.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

struct Agreement {
    size_t pairs = 0;   // within r on the surface, for the queried cells
    size_t missed = 0;  // within 0.9 r on the surface (f ≥ 0.1), not pushing
    size_t through_folds =
        0;                   // pushing, but > 1.1 r apart, or 0.1 r nearer than any path
    double worst_error = 0;  // |distance − exact| / r over the pairs used
    void add(const std::vector<RelaxNeighbour> &used, const std::vector<double> &exact,
             CellId c, double r) {
        std::map<CellId, double> by_id;
        for (const RelaxNeighbour &nb : used) by_id[nb.id] = nb.distance;
        for (CellId p = 0; p < exact.size(); ++p) {
            if (p == c) continue;
            pairs += exact[p] < r;
            const auto it = by_id.find(p);
            if (it == by_id.end()) {
                missed += exact[p] < 0.9 * r;
                continue;
            }
            worst_error = std::max(worst_error, std::abs(it->second - exact[p]) / r);
            through_folds += exact[p] > 1.1 * r || it->second < exact[p] - 0.1 * r;
        }
    }
    double missed_percent() const { return 100.0 * double(missed) / double(pairs); }
};

struct Measured {
    Agreement checked, unfolded, filtered;
};

// The relaxation with exact-geodesic checks, with first-path unfoldings (Teo 2006
// §4.1), and with checked unfoldings built at 1.5 times the radius and filtered down to
// it (as a run's radius shrinks), on the same cells and queries.
Measured measure(const Surface &s, size_t queries) {
    const test::ExactGeodesicOracle oracle(s.mesh);
    const size_t n = 8474;
    const double area = s.mesh.surface_area(), r = 3.3 * std::sqrt(area / double(n));
    Cells cells(s.crps.num_triangles());
    std::vector<test::SurfaceLocation> at;
    for (const SurfacePointSample &p : sample_surface_uniform(s.crps, n, 5)) {
        cells.add({p.tri, p.p}, 0);
        const Vec3d b = s.crps.to_barycentric(p.tri, p.p);
        at.push_back({p.tri, b.y, b.z});
    }
    RelaxContext ctx;
    ctx.crps = &s.crps;
    ctx.r = r;
    Relaxer checked, unfolded, filtered;
    unfolded.neighbourhoods().set_verified(false);
    filtered.neighbourhoods().update(s.crps, 1.5 * r);
    Measured out;
    for (size_t q = 0; q < queries; ++q) {
        const CellId c = CellId(q * (n / queries));
        const std::vector<double> exact = oracle.distances(at[c], at);
        out.checked.add(checked.neighbours(ctx, cells, c), exact, c, r);
        out.unfolded.add(unfolded.neighbours(ctx, cells, c), exact, c, r);
        out.filtered.add(filtered.neighbours(ctx, cells, c), exact, c, r);
    }
    EXPECT_EQ(filtered.neighbourhoods().rebuilds(), 1u);
    EXPECT_EQ(filtered.neighbourhoods().filters(), 1u);
    return out;
}

class RelaxationGeodesics : public ::testing::TestWithParam<const char *> {};

TEST_P(RelaxationGeodesics, NeighboursAreAsFarApartAsTheSurfaceSays) {
    const auto [checked, unfolded, filtered] =
        measure(build_surface(test::sample_mesh(GetParam())), 50);
    std::printf(
        "%s: %zu pairs; checked unfoldings: %.2f %% missed, %zu through folds, "
        "worst error %.2f %% r; filtered from 1.5 r: %.2f %% missed, %zu through folds, "
        "worst error %.2f %% r; first-path unfoldings: %.2f %% missed, %zu through "
        "folds, worst error %.1f %% r\n",
        GetParam(), checked.pairs, checked.missed_percent(), checked.through_folds,
        100 * checked.worst_error, filtered.missed_percent(), filtered.through_folds,
        100 * filtered.worst_error, unfolded.missed_percent(), unfolded.through_folds,
        100 * unfolded.worst_error);
    for (const Agreement *a : {&checked, &filtered}) {
        EXPECT_GT(a->pairs, 1000u);
        EXPECT_EQ(a->through_folds, 0u);
        EXPECT_LE(a->worst_error, 0.08);
        EXPECT_LE(a->missed_percent(), 1.5);
    }
    // The reference the checks exist for: first-path unfoldings of these animals push
    // cells through folds.
    EXPECT_GT(unfolded.through_folds, 0u);
}

INSTANTIATE_TEST_SUITE_P(SampleMeshes, RelaxationGeodesics,
                         ::testing::Values("cow.off", "bull.off", "triceratops.off"),
                         [](const auto &info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace pelage::sim
