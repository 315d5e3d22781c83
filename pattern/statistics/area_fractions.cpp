#include "pattern/statistics/area_fractions.h"

#include "sim/crps/surface_sampling.h"

namespace pelage::pattern::statistics {

AreaFractions measure_area_fractions(const mosaic::MosaicPattern &pattern, size_t samples,
                                     uint64_t seed) {
    AreaFractions a;
    std::vector<size_t> count(pattern.types().size(), 0);
    for (const auto &s :
         sim::sample_surface_uniform(pattern.surface().crps, samples, seed)) {
        const mosaic::ClosestCell c =
            pattern.index().find_nearest(s.tri, {float(s.p.x), float(s.p.y)});
        if (c.index == mosaic::ClosestCell::none) continue;
        ++count[pattern.cells().type[c.index]];
        ++a.samples;
    }
    a.by_type.assign(count.size(), 0.0);
    if (a.samples == 0) return a;
    for (size_t k = 0; k < count.size(); ++k)
        a.by_type[k] = double(count[k]) / double(a.samples);
    return a;
}

}  // namespace pelage::pattern::statistics
