#include "apps/bench/bench_sim_neighbours.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/geodesic/geodesic_mesh.h"
#include "sim/geodesic/window_propagation.h"
#include "sim/mosaic/cells.h"
#include "sim/mosaic/relaxation.h"

namespace pelage::renderer::cli {
namespace {

struct Agreement {
    size_t pairs = 0, missed = 0, through_folds = 0, used = 0;
    double worst_error = 0, error_sum = 0;

    // exact: the geodesic distance to each cell within reach (others are farther).
    void add(const std::vector<sim::RelaxNeighbour> &neighbours,
             const std::map<sim::CellId, double> &exact, double r) {
        std::map<sim::CellId, double> used_by_id;
        for (const sim::RelaxNeighbour &nb : neighbours) used_by_id[nb.id] = nb.distance;
        for (const auto &[id, d] : exact) {
            pairs += d < r;
            if (d < 0.9 * r && !used_by_id.count(id)) ++missed;
        }
        for (const auto &[id, d] : used_by_id) {
            const auto it = exact.find(id);
            const double e = it == exact.end() ? HUGE_VAL : it->second;
            through_folds += e > 1.1 * r || d < e - 0.1 * r;
            if (std::isfinite(e)) {
                worst_error = std::max(worst_error, std::abs(d - e) / r);
                error_sum += std::abs(d - e) / r;
                ++used;
            }
        }
    }
    nlohmann::json json() const {
        return {{"missed_percent", pairs ? 100.0 * double(missed) / double(pairs) : 0.0},
                {"through_folds", through_folds},
                {"worst_error_r", worst_error},
                {"mean_error_r", used ? error_sum / double(used) : 0.0}};
    }
};

}  // namespace

nlohmann::json neighbour_runs(const NeighbourOptions &o) {
    nlohmann::json runs = nlohmann::json::array();
    for (const std::string &path : o.meshes) {
        const sim::Surface s = sim::build_surface(path);
        double area = 0;
        for (sim::TriId t = 0; t < s.crps.num_triangles(); ++t)
            area += s.crps.frame(t).area;
        const double r = o.w_r * std::sqrt(area / double(o.cells));
        sim::Cells cells(s.crps.num_triangles());
        for (const sim::SurfacePointSample &p :
             sim::sample_surface_uniform(s.crps, o.cells, o.seed))
            cells.add({p.tri, p.p}, 0);

        const sim::GeodesicMesh geodesic_mesh(s.crps);
        sim::WindowPropagation propagation(geodesic_mesh);
        std::vector<sim::GeodesicWindow> windows;
        sim::RelaxContext ctx;
        ctx.crps = &s.crps;
        ctx.r = r;
        sim::Relaxer checked, first_path;
        first_path.neighbourhoods().set_verified(false);
        Agreement a_checked, a_first;
        const size_t queries = std::min<size_t>(o.queries, o.cells);
        for (size_t q = 0; q < queries; ++q) {
            const sim::CellId c = sim::CellId(q * (o.cells / queries));
            // Exact distances to every cell within 1.2 r.
            propagation.run(cells.tri(c), cells.pos(c), 1.2 * r, windows);
            std::stable_sort(
                windows.begin(), windows.end(),
                [](const auto &a, const auto &b) { return a.face < b.face; });
            std::map<sim::CellId, double> exact;
            for (size_t i = 0; i < windows.size();) {
                size_t end = i;
                while (end < windows.size() && windows[end].face == windows[i].face)
                    ++end;
                for (sim::CellId p : cells.on(windows[i].face)) {
                    if (p == c) continue;
                    const double d = sim::distance_from_windows(
                        windows.data() + i, windows.data() + end, cells.pos(p));
                    if (std::isfinite(d)) exact[p] = d;
                }
                i = end;
            }
            a_checked.add(checked.neighbours(ctx, cells, c), exact, r);
            a_first.add(first_path.neighbours(ctx, cells, c), exact, r);
        }
        runs.push_back({{"mesh", path},
                        {"cells", o.cells},
                        {"r", r},
                        {"queries", queries},
                        {"pairs", a_checked.pairs},
                        {"checked", a_checked.json()},
                        {"first_path", a_first.json()}});
    }
    return {{"neighbours", runs}};
}

}  // namespace pelage::renderer::cli
