#include "tests/sim/sim_test_util.h"

#include <cmath>
#include <vector>

namespace pelage::test {

double nearest_neighbour_cv(const sim::Crps &crps, const sim::Cells &cells) {
    std::vector<sim::Vec3d> p;
    for (sim::CellId c = 0; c < cells.size(); ++c)
        p.push_back(crps.to_3d(cells.tri(c), cells.pos(c)));
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        double best = 1e300;
        for (size_t j = 0; j < p.size(); ++j)
            if (j != i) best = std::min(best, length_squared(p[i] - p[j]));
        const double d = std::sqrt(best);
        sum += d;
        sum2 += d * d;
    }
    const double n = double(p.size()), mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
}

}  // namespace pelage::test
