#include "shader/clonal_mosaic/coherent_lookup.h"

#include <cmath>

namespace pelage::shader {

ClosestCellIndex::Nearest<3> CoherentLookup::find_three_within(
    const ClosestCellIndex &index, uint64_t serial, sim::TriId t, float b1, float b2,
    float band) {
    if (m_serial == serial && m_tri == t) {
        const Vec2f q = m_frame.point(b1, b2);  // index.point(t, b1, b2), the same bits
        // c1 and c2 at q, the nearer first by (distance, id) as the scan orders.
        const float d1 = squared_distance(m_at[0].x, m_at[0].y, q),
                    d2 = squared_distance(m_at[1].x, m_at[1].y, q);
        const int a = d2 < d1 || (d2 == d1 && m_id[1] < m_id[0]) ? 1 : 0, b = 1 - a;
        const float da = a ? d2 : d1, db = a ? d1 : d2;
        // three_within's cap, and the proof that every other cell lies beyond it.
        const float f1 = std::sqrt(da), cap = f1 + std::max(band, 0.0f);
        // F3 - moved > cap + margin, squared: no square root (nor std::hypot, a libm
        // call) on the way to the decision; the margin dwarfs their rounding.
        const float dx = q.x - m_q.x, dy = q.y - m_q.y;
        const float margin = 1e-4f * (std::abs(q.x) + std::abs(q.y) + cap);
        const float slack = m_f3 - cap - margin;
        if (slack > 0 && dx * dx + dy * dy < slack * slack) {
            ++m_reused;
            ClosestCellIndex::Nearest<3> n;
            n.d2[0] = da;
            n.index[0] = m_cell[a];
            n.nearest_at = m_at[a];
            if (db <= cap * cap) {  // a blend of the two (the band reaches the other)
                n.d2[1] = db;
                n.index[1] = m_cell[b];
            }
            return n;
        }
    }
    ++m_searched;
    const ClosestCellIndex::Nearest<3> n = index.find_three_within(t, b1, b2, band);
    m_serial = 0;
    if (n.index[0] != ClosestCell::none) {
        const uint32_t *id = index.cells().id.data();
        m_serial = serial;
        m_tri = t;
        m_frame = index.frame(t);
        m_q = m_frame.point(b1, b2);
        m_cell[0] = n.index[0];
        m_cell[1] = n.second;
        m_id[0] = id[n.index[0]];
        m_id[1] = n.second != ClosestCell::none ? id[n.second] : 0;
        m_at[0] = n.nearest_at;
        m_at[1] = n.second_at;  // +inf when there is no second cell
        m_f3 = std::sqrt(n.third_d2);
    }
    return n;
}

}  // namespace pelage::shader
