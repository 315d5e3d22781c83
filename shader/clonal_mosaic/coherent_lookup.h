// Reuse of a search's result for coherent queries (camera hits arrive pixel after pixel
// along a tile row, and most fall in the same cell as the hit before).
//
// A search at q0 found the nearest cell c1, the second nearest c2 and a lower bound on
// F3(q0), the distance to the third (what the two-nearest scan saw of the rest:
// ClosestCellIndex::Nearest::third_d2). For a later query q of the same triangle (same
// frame), moved by δ = |q - q0|, every cell other than c1 and c2 is at least F3 - δ
// away from q (triangle inequality). If F3 - δ exceeds F + band', F the nearer of
// |q - c1| and |q - c2|, the banded search at q would find the nearer of the two, and
// the other when it lies within the band, and nothing else — so the scan is skipped.
// Keeping both cells serves the hits along a boundary (the blends of antialiasing) and
// those moving along it: 83 % of the camera hits of sphere_cheetah at 2000 x 2000
// reuse, against 60 % with c1 and F2 alone; the F3 bound costs the scan at most one
// more line.
// The result is the same bits: |q - c1|² is computed from c1's position exactly as the
// scan computes it, and the comparison keeps a relative margin far above float
// rounding. Keyed by an index serial (callers give each index a number never reused,
// not its address) and the triangle.
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
    ClosestCellIndex::Frame m_frame{};  // the triangle's (a copy: no index read to reuse)
    Vec2f m_q;                          // the search's query, in the triangle's frame
    uint32_t m_cell[2]{};               // c1, c2 (none: no second cell)
    uint32_t m_id[2]{};                 // their stable ids (ties)
    Vec2f m_at[2];                      // their positions (+inf: none)
    float m_f3 = 0;                     // a lower bound on the search's F3
    size_t m_reused = 0, m_searched = 0;
};

}  // namespace pelage::shader
