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
// those moving along it, which c1 and F2 alone would send back to the scan; most
// camera hits reuse (the renderer runs a tile's rows back and forth). The F3 bound
// costs the scan at most one more line, and the exact F3 would save few searches.
// The result is the same bits: |q - c1|² is computed from c1's position exactly as the
// scan computes it, and the comparison keeps a relative margin far above float
// rounding. Only queries in the search's region of the triangle reuse it: a cell's
// listed position may differ between regions. Keyed by an index serial (callers give each
// index a number never reused, not its address) and the triangle.
//
// One object per thread (the plugin keeps it thread_local); not thread-safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "pattern/mosaic/closest_cell.h"
#include "pattern/mosaic/subdivision.h"

namespace pelage::pattern::mosaic {

class CoherentLookup {
  public:
    using Result = ClosestCellIndex::Nearest<3>;

    // ClosestCellIndex::find_three_within(t, b1, b2, band) of `index`, whose results it
    // equals bit for bit; `serial` identifies the index (never 0).
    Result find_three_within(const ClosestCellIndex &index, uint64_t serial, sim::TriId t,
                             float b1, float b2, float band) {
        Result n;
        if (reuse(serial, t, b1, b2, band, n)) return n;
        return search(index, serial, t, b1, b2, band);
    }

    // The reuse alone, inline, for callers with a fast path of their own: true, with
    // `n` set (c1, and c2 when the band reaches it), when the last search's result
    // provably answers the query; false when it takes search().
    bool reuse(uint64_t serial, sim::TriId t, float b1, float b2, float band, Result &n) {
        if (m_serial != serial || m_tri != t) return false;
        if (m_regions > 1 && slot_at(m_regions, b1, b2) != m_slot) return false;
        const Vec2f q = m_frame.point(b1, b2);  // index.point(t, b1, b2), the same bits
        // c1 and c2 at q, the nearer first by (distance, id) as the scan orders.
        const float d1 = squared_distance(m_at[0].x, m_at[0].y, q),
                    d2 = squared_distance(m_at[1].x, m_at[1].y, q);
        const int a = d2 < d1 || (d2 == d1 && m_id[1] < m_id[0]) ? 1 : 0, b = 1 - a;
        const float da = a ? d2 : d1, db = a ? d1 : d2;
        // three_within's cap, and the proof that every other cell lies beyond it.
        const float f1 = std::sqrt(da), cap = f1 + std::max(band, 0.0f);
        // F3 - margin - moved > cap, squared: no square root (nor std::hypot, a libm
        // call) on the way to the decision; the margin (set by search()) dwarfs their
        // rounding.
        const float dx = q.x - m_q.x, dy = q.y - m_q.y;
        const float slack = m_f3_less_margin - cap;
        if (!(slack > 0 && dx * dx + dy * dy < slack * slack)) return false;
        ++m_reused;
        n.d2[0] = da;
        n.index[0] = m_cell[a];
        n.nearest_at = m_at[a];
        if (db <= cap * cap) {  // a blend of the two (the band reaches the other)
            n.d2[1] = db;
            n.index[1] = m_cell[b];
        }
        if (m_bent) m_index->resolve(n, q);
        return true;
    }
    // The search, remembered for the next queries (out of line: the cold path).
    Result search(const ClosestCellIndex &index, uint64_t serial, sim::TriId t, float b1,
                  float b2, float band);

    size_t reused() const { return m_reused; }
    size_t searched() const { return m_searched; }

  private:
    uint64_t m_serial = 0;  // 0: nothing to reuse
    sim::TriId m_tri = 0;
    uint32_t m_regions = 1, m_slot = 0;  // the search's region of the triangle
    TriangleFrame m_frame{};  // the triangle's (a copy: no index read to reuse)
    Vec2f m_q;                // the search's query, in the triangle's frame
    const ClosestCellIndex *m_index = nullptr;  // the index of m_serial
    uint32_t m_cell[2]{};  // c1, c2 as list entries (none: no second cell)
    bool m_bent = false;   // either is a bent entry
    uint32_t m_id[2]{};    // their stable ids (ties)
    Vec2f m_at[2];         // their positions (+inf: none)
    // A lower bound on the search's F3, less a margin for float rounding (search()).
    float m_f3_less_margin = 0;
    size_t m_reused = 0, m_searched = 0;
};

}  // namespace pelage::pattern::mosaic
