#include "sim/mosaic/final_cells.h"

#include <algorithm>
#include <array>
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

    // The mean counts by type: a type-i cell divides at rate λ_i and its child is of
    // type j with probability mutation[i][j], so dn_j/dt = Σ_i λ_i·n_i·mutation[i][j].
    // λ_i = 1/D_i for exponential delays; ln 2/D_i for Poisson ones, whose delays are
    // about D_i each (a doubling per D_i). Integrated with the midpoint rule in steps of
    // a tenth of the shortest division time.
    const int k = types.size();
    std::array<double, max_cell_types> rate{}, n{};
    double shortest = params.end_time;
    for (int i = 0; i < k; ++i) {
        n[i] = n0 * types[i].initial_probability;
        if (!types[i].divides()) continue;
        rate[i] = (params.division_distribution == DivisionDistribution::exponential
                       ? 1.0
                       : std::log(2.0)) /
                  types[i].division_time;
        shortest = std::min(shortest, types[i].division_time);
    }
    const auto derivative = [&](const std::array<double, max_cell_types> &m) {
        std::array<double, max_cell_types> d{};
        for (int i = 0; i < k; ++i)
            for (int j = 0; j < k; ++j) d[j] += rate[i] * m[i] * types.mutation(i, j);
        return d;
    };
    const int steps =
        std::clamp(int(std::ceil(10 * params.end_time / shortest)), 1, 100000);
    const double h = params.end_time / steps;
    double total = n0;
    for (int s = 0; s < steps; ++s) {
        std::array<double, max_cell_types> mid = n;
        const auto d0 = derivative(n);
        for (int i = 0; i < k; ++i) mid[i] += 0.5 * h * d0[i];
        const auto d1 = derivative(mid);
        total = 0;
        for (int i = 0; i < k; ++i) total += (n[i] += h * d1[i]);
        if (target > 0 && total >= target) return target;
        if (!(total < 1e12)) return 1e12;  // far beyond anything a run can hold
    }
    return std::max(total, n0);
}

}  // namespace pelage::sim
