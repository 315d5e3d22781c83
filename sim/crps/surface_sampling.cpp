#include "sim/crps/surface_sampling.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace pelage::sim {

std::vector<SurfacePointSample> sample_surface_uniform(const Crps &crps, size_t n,
                                                       uint64_t seed) {
    const size_t nt = crps.num_triangles();
    std::vector<double> cdf(nt);
    double sum = 0;
    for (TriId t = 0; t < nt; ++t) cdf[t] = (sum += crps.frame(t).area);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::vector<SurfacePointSample> out;
    out.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const double pick = u01(rng) * sum;
        const TriId t = static_cast<TriId>(std::min<size_t>(
            std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(), nt - 1));
        const double s = std::sqrt(u01(rng)), r = u01(rng);
        out.push_back({t, crps.barycentric_to_2d(t, {1 - s, s * (1 - r), s * r})});
    }
    return out;
}

}  // namespace pelage::sim
