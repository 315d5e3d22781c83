#include "sim/mosaic/cells.h"

#include <algorithm>

namespace pelage::sim {

CellId Cells::add(SurfacePoint at, uint8_t type, CellId founder) {
    const CellId id = static_cast<CellId>(m_tri.size());
    m_founder.push_back(founder == none ? id : founder);
    m_tri.push_back(at.tri);
    m_x.push_back(at.p.x);
    m_z.push_back(at.p.y);
    m_type.push_back(type);
    m_buckets[at.tri].push_back(id);
    return id;
}

void Cells::move(CellId c, SurfacePoint to) {
    if (to.tri != m_tri[c]) {
        auto &from = m_buckets[m_tri[c]];
        from.erase(std::find(from.begin(), from.end(), c));
        m_buckets[to.tri].push_back(c);
        m_tri[c] = to.tri;
    }
    m_x[c] = to.p.x;
    m_z[c] = to.p.y;
}

void Cells::reserve(size_t n) {
    m_tri.reserve(n);
    m_x.reserve(n);
    m_z.reserve(n);
    m_type.reserve(n);
    m_founder.reserve(n);
}

}  // namespace pelage::sim
