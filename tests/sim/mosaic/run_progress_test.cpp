// A run's progress follows the work (cells relaxed per step), not the step count: on an
// exponentially growing count it matches the exact share of the cell-steps, for a run
// to end_time and for one to a target count, it follows growth that speeds up once the
// faster growth shows, and it is the step count when nothing grows.
#include "sim/mosaic/run_progress.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace pelage::sim {
namespace {

// round(m0 · g^(s+1)) cells after step s, capped at `cap`.
std::vector<uint64_t> growth(double m0, double g, int steps, double cap = HUGE_VAL) {
    std::vector<uint64_t> m;
    for (int s = 0; s < steps; ++s)
        m.push_back(uint64_t(std::llround(std::min(cap, m0 * std::pow(g, s + 1)))));
    return m;
}

// The exact fraction after each step: cells summed so far over the whole sum.
std::vector<double> exact_fractions(const std::vector<uint64_t> &m) {
    double total = 0, sum = 0;
    for (uint64_t c : m) total += double(c);
    std::vector<double> f;
    for (uint64_t c : m) f.push_back((sum += double(c)) / total);
    return f;
}

TEST(RunProgress, ExponentialGrowthToEndTimeFollowsTheWork) {
    const std::vector<uint64_t> m = growth(100, 1.05, 100);
    const std::vector<double> exact = exact_fractions(m);
    RunProgress p(100, 0, 100);
    double worst = 0, worst_by_steps = 0;
    for (size_t s = 0; s < m.size(); ++s) {
        const double f = p.after_step(s, m[s]);
        worst = std::max(worst, std::abs(f - exact[s]));
        worst_by_steps = std::max(worst_by_steps, std::abs((s + 1) / 100.0 - exact[s]));
    }
    EXPECT_LT(worst, 0.01);
    EXPECT_GT(worst_by_steps, 0.4);  // what a count of steps shows
    // Half the steps are about a twelfth of the work.
    RunProgress half(100, 0, 100);
    double f = 0;
    for (size_t s = 0; s < 50; ++s) f = half.after_step(s, m[s]);
    EXPECT_NEAR(f, exact[49], 0.005);
    EXPECT_LT(f, 0.1);
}

TEST(RunProgress, OpenEndedRunToATargetFollowsTheWork) {
    // 100 → 10 000 cells at 5 % a step: 95 steps, the last at the target.
    const std::vector<uint64_t> m = growth(100, 1.05, 95, 10000);
    ASSERT_EQ(m.back(), 10000u);
    const std::vector<double> exact = exact_fractions(m);
    RunProgress p(0, 10000, 100);
    double worst = 0;
    for (size_t s = 0; s < m.size(); ++s)
        worst = std::max(worst, std::abs(p.after_step(s, m[s]) - exact[s]));
    EXPECT_LT(worst, 0.02);
    // With end_time too, the sooner of the two ends the estimate.
    RunProgress both(1000, 10000, 100);
    worst = 0;
    for (size_t s = 0; s < m.size(); ++s)
        worst = std::max(worst, std::abs(both.after_step(s, m[s]) - exact[s]));
    EXPECT_LT(worst, 0.02);
}

TEST(RunProgress, GrowthThatSpeedsUpIsFollowedFromItsRecentRate) {
    // A lag (0.1 % a step) then fast growth (3 % a step), as when a fast-dividing type
    // takes over: most of the work is in the last steps.
    std::vector<uint64_t> m;
    double c = 1000;
    for (int s = 0; s < 300; ++s) m.push_back(uint64_t(c *= s < 100 ? 1.001 : 1.03));
    const std::vector<double> exact = exact_fractions(m);
    RunProgress p(300, 0, 1000);
    // During the lag nothing tells what is coming; once the fast growth is in the
    // window, the estimate follows it.
    double worst = 0;
    for (size_t s = 0; s < m.size(); ++s) {
        const double f = p.after_step(s, m[s]);
        if (s >= 150) worst = std::max(worst, std::abs(f - exact[s]));
        if (s == 149) {
            EXPECT_LT(f, 0.1) << "half the steps, " << exact[s] << " of the work";
        }
    }
    EXPECT_LT(worst, 0.02);
}

TEST(RunProgress, NoGrowthIsTheStepCount) {
    RunProgress p(40, 0, 500);
    for (uint64_t s = 0; s < 40; ++s)
        EXPECT_NEAR(p.after_step(s, 500), double(s + 1) / 40, 1e-12) << s;
    RunProgress open(0, 1000, 500);
    EXPECT_EQ(open.after_step(0, 500), 0.0);  // nothing to extrapolate from yet
    EXPECT_EQ(open.after_step(1, 1000), 1.0);
}

}  // namespace
}  // namespace pelage::sim
