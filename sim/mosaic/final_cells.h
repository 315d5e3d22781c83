// How many cells a run is expected to end with, before it runs: what the simulation
// surface's resolution is chosen from (sim/remesh/cell_scale_surface.h).
//
// A run stops at target_cells when one is set (scaled with the initial count as
// CmSimulation::initialize does), or at end_time. Up to then the counts by type follow
// the mean of the division process (Walter 1998 §3.4): each type divides at its own
// rate and its children take their types from its mutation row, so a type that only
// arises by mutation and divides fast (walter-ocelot's) is counted. The estimate is of
// the right order, which is all a mesh resolution needs.
#pragma once

#include <cstdint>

#include "sim/mosaic/cell_types.h"

namespace pelage::sim {

double expected_final_cells(const SimParams &params, const CellTypes &types,
                            uint64_t initial_cells);

}  // namespace pelage::sim
