// The K nearest cells (K = 1, 2) of a list of CellBlocks, lane by lane: a block's five
// cells side by side in vector lanes, each lane keeping the K nearest of the cells it has
// seen, with selects only, and the lanes merged at the end. Nothing branches on which of
// two distances is smaller — in a list in no useful order (random and indirect hits) that
// is a coin toss, on which the insertion scan's branches mispredict. What
// ClosestCellIndex::find() and find_nearest() run, and, at eight lanes, the banded
// search's first pass (closest_cell.cpp), with Teo's pruning (Fig. 6.2): blocks are
// sorted by bound, and the scan stops at the first whose bound lies beyond the K-th
// nearest so far.
//
// Two widths, the same results bit for bit (the same lanes, the same float operations, no
// fused multiply-add): four lanes and one, SSE2 (every x86-64; NEON on ARM), and eight
// lanes, one block in one AVX2 register, chosen at run time when the CPU has AVX2.
#pragma once

#include <cstdint>

#include "pattern/mosaic/cell_block.h"

namespace pelage::pattern::mosaic {

// What a lane scan found. Cells are named by their slot in the list (block × 5 + lane),
// read by the caller; squared distances.
struct LaneScan {
    const CellBlock *stop =
        nullptr;           // the first block not scanned (the end when all were)
    float f1 = 0, f2 = 0;  // the nearest, second nearest (K = 2; +inf: none)
    uint32_t slot1 = 0, slot2 = 0;
    float rest = 0;  // the least distance of the scanned cells not among the K
    // An exact tie among the K + 1 nearest: then the order by (distance, stable id) needs
    // the ids, and the caller rescans with the insertion scan. (Rare: equal floats of
    // distinct points.)
    bool tie = false;
};

using LaneScanFn = LaneScan (*)(const CellBlock *begin, const CellBlock *end, Vec2f q);

struct LaneScanners {
    LaneScanFn nearest = nullptr;      // K = 1
    LaneScanFn nearest_two = nullptr;  // K = 2
    int lanes = 0;                     // 4 or 8: which width they are
};

// The widest scanners this CPU runs (wide = false: the four-lane ones, for tests and
// benchmarks that compare the two).
LaneScanners lane_scanners(bool wide = true);

namespace detail {
// lane_scan_wide.cpp: the eight-lane scanners, or lanes == 0 when the CPU (or the build's
// target) has no AVX2.
LaneScanners wide_lane_scanners();
}  // namespace detail

}  // namespace pelage::pattern::mosaic
