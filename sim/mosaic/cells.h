// The cells of a Clonal Mosaic, structure of arrays. A cell's index is
// its creation order and its stable id: cells are never destroyed, so ids are dense.
// Each triangle keeps the list of cells living on it (its "bucket"), in a deterministic
// order that the relaxation's fixed summation order relies on.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/crps/cell_walk.h"

namespace pelage::sim {

using CellId = uint32_t;

class Cells {
  public:
    explicit Cells(size_t num_triangles = 0) : m_buckets(num_triangles) {}

    size_t size() const { return m_tri.size(); }
    size_t num_triangles() const { return m_buckets.size(); }

    // `founder`: the initial cell whose clone this cell belongs to (the founder of the
    // dividing parent); none: this cell is a founder itself.
    static constexpr CellId none = ~CellId(0);
    CellId add(SurfacePoint at, uint8_t type, CellId founder = none);
    // Moves cell c to `to`, keeping buckets consistent (appends to the new bucket).
    void move(CellId c, SurfacePoint to);
    // Changes c's type (a neural-crest mask switching it, sim/control).
    void set_type(CellId c, uint8_t type) { m_type[c] = type; }

    TriId tri(CellId c) const { return m_tri[c]; }
    Vec2d pos(CellId c) const { return {m_x[c], m_z[c]}; }
    uint8_t type(CellId c) const { return m_type[c]; }
    CellId founder(CellId c) const { return m_founder[c]; }
    const std::vector<CellId> &on(TriId t) const { return m_buckets[t]; }

    const std::vector<double> &x() const { return m_x; }
    const std::vector<double> &z() const { return m_z; }
    const std::vector<uint8_t> &types() const { return m_type; }
    const std::vector<TriId> &tris() const { return m_tri; }

    void reserve(size_t n);

  private:
    std::vector<TriId> m_tri;
    std::vector<double> m_x, m_z;
    std::vector<uint8_t> m_type;
    std::vector<CellId> m_founder;
    std::vector<std::vector<CellId>> m_buckets;
};

}  // namespace pelage::sim
