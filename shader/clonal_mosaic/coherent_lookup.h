// Reuse of the previous lookup for coherent queries (camera hits arrive pixel after pixel
// along a tile row, and most fall in the same cell as the hit before).
//
// After a search at q_prev found a single cell c within F1 + band, we know F2(q_prev),
// the distance to the second-nearest cell. For the next query q of the same triangle
// (same frame), moved by δ = |q - q_prev|, every other cell is at least F2 - δ away from
// q (triangle inequality). If F2 - δ > |q - c| + band', the banded search at q would
// find c alone — so the scan is skipped. The result is the same bits: |q - c|² is
// computed from c's position exactly as the scan computes it, and the comparison keeps a
// relative margin far above float rounding. Keyed by an index serial (callers give each
// index a number never reused, not its address) and the triangle.
//
// One object per thread (the plugin keeps it thread_local); not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "shader/clonal_mosaic/closest_cell.h"

namespace pelage::shader {

class CoherentLookup {
  public:
    // ClosestCellIndex::find_three_within(t, b1, b2, band) of `index`, whose results it
    // equals bit for bit; `serial` identifies the index (never 0).
    ClosestCellIndex::Nearest<3> find_three_within(const ClosestCellIndex &index,
                                                   uint64_t serial, sim::TriId t,
                                                   float b1, float b2, float band);

    size_t reused() const { return m_reused; }
    size_t searched() const { return m_searched; }

  private:
    uint64_t m_serial = 0;  // 0: nothing to reuse
    sim::TriId m_tri = 0;
    uint32_t m_cell = 0;
    Vec2f m_q, m_at;  // the last query and its single cell, in the triangle's frame
    float m_f2 = 0;   // the last query's distance to the second-nearest cell
    size_t m_reused = 0, m_searched = 0;
};

}  // namespace pelage::shader
