// Cells per unit area over a growing run (sim/mosaic/growing_surface.h), shared by the
// growth tests: Walter's thesis §6.2 keeps it constant while the surface grows.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/mosaic/growing_surface.h"

namespace pelage::test {

// The largest relative deviation of cells per unit area from the first sample's.
inline double max_density_deviation(const std::vector<sim::GrowthSample> &samples) {
    const double d0 = double(samples[0].cells) / samples[0].area;
    double m = 0;
    for (const sim::GrowthSample &g : samples)
        m = std::max(m, std::abs(double(g.cells) / g.area / d0 - 1));
    return m;
}

inline void expect_density_within(const std::vector<sim::GrowthSample> &samples,
                                  double tolerance) {
    ASSERT_GE(samples.size(), 2u);
    const double d0 = double(samples[0].cells) / samples[0].area;
    for (const sim::GrowthSample &g : samples)
        EXPECT_NEAR(double(g.cells) / g.area / d0, 1.0, tolerance)
            << "at t = " << g.time << ": " << g.cells << " cells on area " << g.area;
}

}  // namespace pelage::test
