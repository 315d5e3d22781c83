// The expected final cell count (final_cells.h) against closed forms of the mean
// division process.
#include "sim/mosaic/final_cells.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pelage::sim {
namespace {

CellType type(const char *name, double division_time, double initial_probability) {
    CellType t;
    t.name = name;
    t.division_time = division_time;
    t.initial_probability = initial_probability;
    return t;
}

TEST(FinalCells, OneTypeGrowsExponentially) {
    const CellTypes types({type("F", 2.0, 1.0)}, {{1.0}}, {{0.0}});
    SimParams p;
    p.end_time = 6;
    p.division_distribution = DivisionDistribution::exponential;
    // A Yule process of rate 1/D: n0·e^(T/D).
    EXPECT_NEAR(expected_final_cells(p, types, 100), 100 * std::exp(3.0),
                0.01 * 100 * 20);
    // Poisson delays of mean D: a doubling per D, n0·2^(T/D).
    p.division_distribution = DivisionDistribution::poisson;
    EXPECT_NEAR(expected_final_cells(p, types, 100), 800, 8);
}

TEST(FinalCells, AMutantTypeIsCounted) {
    // F divides at rate 1/D and every child is B, which never divides: F stays n0 and
    // B grows as n0·t/D.
    const CellTypes types({type("F", 4.0, 1.0), type("B", HUGE_VAL, 0.0)},
                          {{0.0, 1.0}, {0.0, 1.0}}, {{0.0, 0.0}, {0.0, 0.0}});
    SimParams p;
    p.end_time = 20;
    p.division_distribution = DivisionDistribution::exponential;
    EXPECT_NEAR(expected_final_cells(p, types, 1000), 1000 + 1000 * 20 / 4.0, 1.0);
}

TEST(FinalCells, TheTargetStopsTheRun) {
    const CellTypes types({type("F", 1.0, 1.0)}, {{1.0}}, {{0.0}});
    SimParams p;
    p.end_time = 50;
    p.initial_cells = 500;
    p.target_cells = 2000;
    // Scaled with the initial count as CmSimulation::initialize does.
    EXPECT_DOUBLE_EQ(expected_final_cells(p, types, 1000), 4000);
    p.end_time = 0;
    EXPECT_DOUBLE_EQ(expected_final_cells(p, types, 1000), 4000);
}

}  // namespace
}  // namespace pelage::sim
