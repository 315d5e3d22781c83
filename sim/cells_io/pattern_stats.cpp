#include "sim/cells_io/pattern_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sim/core/disjoint_sets.h"

namespace pelage::sim {

PatternStats compute_pattern_stats(const CellsData &d) {
    PatternStats s;
    const size_t n = d.num_cells();
    s.total_cells = n;
    s.area = d.area();
    std::vector<size_t> count(d.types.size(), 0);
    for (uint8_t t : d.type) ++count[t];
    for (size_t i = 0; i < d.types.size(); ++i)
        s.cells_by_type.emplace_back(d.types[i].name, count[i]);
    const int F = find_type(d, "F", 0), B = find_type(d, "B", 1);
    const size_t nf = F >= 0 ? count[F] : 0, nb = B >= 0 && B != F ? count[B] : 0;
    s.spot_fraction = nf + nb > 0 ? double(nf) / double(nf + nb) : 0.0;
    if (nf == 0) return s;

    // --- Connected F cells through the triangle and its 1-ring (maps F[j→t]) ---
    const double delta = 1.5 * std::sqrt(s.area / double(n)), delta2 = delta * delta;
    DisjointSets sets(n);
    const size_t nt = d.num_triangles();
    for (TriId t = 0; t < nt; ++t) {
        for (uint32_t a = d.cell_row[t]; a < d.cell_row[t + 1]; ++a) {
            if (d.type[a] != F) continue;
            const Vec2d pa{d.x[a], d.z[a]};
            for (uint32_t b = a + 1; b < d.cell_row[t + 1]; ++b)
                if (d.type[b] == F && length_squared(Vec2d{d.x[b], d.z[b]} - pa) < delta2)
                    sets.unite(a, b);
            for (uint32_t k = d.nbr_row[t]; k < d.nbr_row[t + 1]; ++k) {
                const TriId j = d.nbr[k];
                if (j < t) continue;  // each pair of triangles once
                const RigidMap2 &Fjt = d.to_master[k];
                for (uint32_t b = d.cell_row[j]; b < d.cell_row[j + 1]; ++b)
                    if (d.type[b] == F &&
                        length_squared(Fjt.apply({d.x[b], d.z[b]}) - pa) < delta2)
                        sets.unite(a, b);
            }
        }
    }
    std::vector<size_t> size(n, 0);
    for (uint32_t c = 0; c < n; ++c)
        if (d.type[c] == F) ++size[sets.find(c)];
    for (size_t c = 0; c < n; ++c)
        if (size[c] > 0) {
            ++s.spots;
            s.largest_spot_cells = std::max(s.largest_spot_cells, size[c]);
            s.spot_areas.push_back(double(size[c]) * (s.area / double(n)));
        }
    std::sort(s.spot_areas.begin(), s.spot_areas.end());
    s.mean_spot_area = double(nf) * (s.area / double(n)) / double(s.spots);
    return s;
}

}  // namespace pelage::sim

namespace pelage::sim {

double quantile(const std::vector<double> &v, double q) {
    if (v.empty()) return 0;
    const double x = std::clamp(q, 0.0, 1.0) * double(v.size() - 1);
    const size_t i = size_t(x);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (v[i + 1] - v[i]) * (x - double(i));
}

}  // namespace pelage::sim
