#include "pattern/mosaic/coherent_lookup.h"

#include <cmath>

#include "pattern/mosaic/subdivision.h"

namespace pelage::pattern::mosaic {

CoherentLookup::Result CoherentLookup::search(const ClosestCellIndex &index,
                                              uint64_t serial, sim::TriId t, float b1,
                                              float b2, float band) {
    ++m_searched;
    // Selection by listed positions (what the search does), remembered as list entries;
    // bent entries' exact distances come from the index, here and at every reuse.
    ClosestCellIndex::Nearest<3> n = index.find_three_within_listed(t, b1, b2, band);
    m_serial = 0;
    if (n.index[0] != ClosestCell::none) {
        const uint32_t *id = index.cells().id.data();
        m_serial = serial;
        m_index = &index;
        m_tri = t;
        m_regions = index.regions_per_side(t);
        m_slot = m_regions > 1 ? slot_at(m_regions, b1, b2) : 0;
        m_frame = index.frame(t);
        m_q = m_frame.point(b1, b2);
        m_cell[0] = n.index[0];
        m_cell[1] = n.second;
        auto bent = [](uint32_t e) { return e != ClosestCell::none && (e & bent_flag); };
        m_bent = bent(m_cell[0]) || bent(m_cell[1]);
        m_id[0] = id[index.cell_of(n.index[0])];
        m_id[1] = n.second != ClosestCell::none ? id[index.cell_of(n.second)] : 0;
        m_at[0] = n.nearest_at;
        m_at[1] = n.second_at;  // +inf when there is no second cell
        // The margin is relative to the coordinates' and distances' size: 1e-4 of
        // |q.x| + |q.y| + cap, far above float rounding. Taken once here, bounded over
        // every query that can pass the test: it moves less than F3 from m_q (so
        // |q.x| + |q.y| grows by under 1.5 F3) and its cap is under F3.
        const float f3 = std::sqrt(n.third_d2);
        m_f3_less_margin =
            std::isinf(f3) ? f3
                           : f3 - 1e-4f * (std::abs(m_q.x) + std::abs(m_q.y) + 3 * f3);
    }
    index.resolve(n, m_frame.point(b1, b2));
    return n;
}

}  // namespace pelage::pattern::mosaic
