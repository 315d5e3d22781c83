// The share of the surface each cell type covers, as the renderer shows it: n
// area-uniform surface points (sim/crps/surface_sampling.h), each taking the type of its
// nearest cell found by the renderer's closest-cell search. Walter (thesis §3.5) reports
// a pattern's "spot area" from cell counts; when the adhesions differ between types,
// cells of one type pack more densely than the other's and counts overstate that type's
// area, so the look is measured by area. A fraction f measured with n points has a
// standard error of sqrt(f (1 - f) / n).
#pragma once

#include <cstdint>
#include <vector>

#include "pattern/mosaic/pattern.h"

namespace pelage::pattern::statistics {

struct AreaFractions {
    std::vector<double> by_type;  // indexed like the pattern's types; sums to 1
    size_t samples = 0;           // points that found a cell
};

// Deterministic for a given seed. Points with no reachable cell (an empty mosaic) are
// not counted.
AreaFractions measure_area_fractions(const mosaic::MosaicPattern &pattern, size_t samples,
                                     uint64_t seed);

}  // namespace pelage::pattern::statistics
