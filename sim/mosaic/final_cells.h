// How many cells a run is expected to end with, before it runs: what the simulation
// surface's resolution is chosen from (sim/remesh/cell_scale_surface.h).
//
// A run stops at target_cells when one is set (scaled with the initial count as
// CmSimulation::initialize does), else at end_time. Up to end_time each initial type
// grows as a pure birth process with its own mean division time D (Walter 1998 §3.4):
// by 2^(T/D) with Poisson-distributed delays (mean D, so about T/D generations), by
// e^(T/D) with exponential delays (a Yule process of rate 1/D). Mutation is ignored: it
// moves cells between types but each child still divides at its new type's rate, so the
// estimate is of the right order, which is all a mesh resolution needs.
#pragma once

#include <cstdint>

#include "sim/mosaic/cell_types.h"

namespace pelage::sim {

double expected_final_cells(const SimParams &params, const CellTypes &types,
                            uint64_t initial_cells);

}  // namespace pelage::sim
