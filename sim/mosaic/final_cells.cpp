#include "sim/mosaic/final_cells.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {

double expected_final_cells(const SimParams &params, const CellTypes &types,
                            uint64_t initial_cells) {
    const double n0 = double(initial_cells);
    double target = 0;
    if (params.target_cells > 0)
        target = params.initial_cells > 0
                     ? double(params.target_cells) * n0 / double(params.initial_cells)
                     : double(params.target_cells);
    if (params.end_time <= 0) return std::max(n0, target);

    double grown = 0;
    for (int k = 0; k < types.size(); ++k) {
        const CellType &type = types[k];
        double factor = 1;
        if (type.divides()) {
            const double generations = params.end_time / type.division_time;
            factor = params.division_distribution == DivisionDistribution::exponential
                         ? std::exp(std::min(generations, 700.0))
                         : std::exp2(std::min(generations, 1000.0));
        }
        grown += n0 * type.initial_probability * factor;
    }
    grown = std::max(grown, n0);
    return target > 0 ? std::min(grown, target) : grown;
}

}  // namespace pelage::sim
