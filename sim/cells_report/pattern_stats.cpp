#include "sim/cells_report/pattern_stats.h"

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
    return s;
}

}  // namespace pelage::sim
