#include "shader/clonal_mosaic/coherent_lookup.h"

#include <cmath>

namespace pelage::shader {

ClosestCellIndex::Nearest<3> CoherentLookup::find_three_within(
    const ClosestCellIndex &index, uint64_t serial, sim::TriId t, float b1, float b2,
    float band) {
    const Vec2f q = index.point(t, b1, b2);
    if (m_serial == serial && m_tri == t) {
        const float d2 = squared_distance(m_at.x, m_at.y, q), f1 = std::sqrt(d2);
        // Not std::hypot: these are small coordinates, and hypot is a libm call that
        // cost as much as the rest of the check.
        const float dx = q.x - m_q.x, dy = q.y - m_q.y;
        const float moved = std::sqrt(dx * dx + dy * dy);
        const float margin = 1e-4f * (std::abs(q.x) + std::abs(q.y) + f1 + band);
        const float need = f1 + band + margin;
        if (squared_distance(m_at2.x, m_at2.y, q) > need * need && m_f3 - moved > need) {
            ++m_reused;
            ClosestCellIndex::Nearest<3> n;
            n.d2[0] = d2;
            n.index[0] = m_cell;
            n.nearest_at = m_at;
            return n;
        }
    }
    ++m_searched;
    const ClosestCellIndex::Nearest<3> n = index.find_three_within(t, b1, b2, band);
    m_serial = 0;
    if (n.index[0] != ClosestCell::none) {
        m_serial = serial;
        m_tri = t;
        m_cell = n.index[0];
        m_q = q;
        m_at = n.nearest_at;
        m_at2 = n.second_at;
        m_f3 = std::sqrt(n.third_d2);
    }
    return n;
}

}  // namespace pelage::shader
