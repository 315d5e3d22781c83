// Counts of a Clonal Mosaic (Walter thesis §3.5): cells by type and the spot fraction
// F/(F+B) (Walter's "spot area", computed from counts: 100·F/(F+B) reproduces every
// value he lists). Spots themselves are measured on the surface as the renderer shows
// them, through the closest-cell search (pattern/statistics/spot_statistics.h): one
// definition for `pelage stats`, the renderer and the baselines.
#pragma once

#include <string>
#include <vector>

#include "sim/cells_io/cells_file.h"

namespace pelage::sim {

struct PatternStats {
    std::vector<std::pair<std::string, size_t>> cells_by_type;
    size_t total_cells = 0;
    double area = 0;
    double spot_fraction = 0;  // F / (F + B); 0 when there is neither
};

PatternStats compute_pattern_stats(const CellsData &data);

}  // namespace pelage::sim
