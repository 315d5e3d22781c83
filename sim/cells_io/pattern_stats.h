// Pattern statistics of a Clonal Mosaic (Walter thesis §3.5): cells by type, the spot
// fraction F/(F+B) (Walter's "spot area", computed from counts: 100·F/(F+B) reproduces
// every value he lists), and spots = connected components of the F cells' Voronoi
// regions on the surface.
//
// Approximation (documented, not Walter's): two F cells are taken as Voronoi neighbours
// when their surface distance (through the CRPS maps of the triangle's 1-ring) is below
// 1.5·sqrt(A/m), i.e. between the first (~1.07·sqrt(A/m)) and second (~1.86·sqrt(A/m))
// neighbour rings of a hexagonal packing; each cell's Voronoi area is taken as A/m.
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
    size_t spots = 0;
    double mean_spot_area = 0;  // surface area units
    size_t largest_spot_cells = 0;
    std::vector<double> spot_areas;  // every spot's area (its cells × A/m), ascending
};

// The q-quantile (q in [0, 1]) of ascending values, linear between order statistics;
// 0 for none.
double quantile(const std::vector<double> &ascending, double q);

PatternStats compute_pattern_stats(const CellsData &data);

}  // namespace pelage::sim
