// The windows of many point sources (the cells of a mosaic), grouped by triangle: what
// the closest-cell search needs to know about a triangle is every source's windows on
// it. Each source propagates on its own (window_propagation.h) within a radius, in
// parallel; the grouping keeps source order within a triangle, so the result does not
// depend on the number of threads.
#pragma once

#include <span>
#include <vector>

#include "sim/crps/cell_walk.h"
#include "sim/geodesic/window_propagation.h"

namespace pelage::sim {

struct SourcedWindow {
    uint32_t source;  // index into the sources given to build()
    GeodesicWindow window;
};

class WindowsByFace {
  public:
    // Windows of every source within `radius`.
    void build(const GeodesicMesh &mesh, std::span<const SurfacePoint> sources,
               double radius);
    // Windows of source i within radii[i] (none when radii[i] <= 0). When `faces` is
    // non-empty, only windows on triangles t with faces[t] != 0 are kept.
    void build(const GeodesicMesh &mesh, std::span<const SurfacePoint> sources,
               std::span<const double> radii, std::span<const uint8_t> faces = {});

    std::span<const SourcedWindow> of(TriId t) const {
        return {m_windows.data() + m_row[t], m_row[t + 1] - m_row[t]};
    }
    size_t size() const { return m_windows.size(); }
    // Windows settled by the last build's propagations, kept or not: its work.
    size_t settled() const { return m_settled; }
    size_t bytes() const {
        return m_windows.size() * sizeof(SourcedWindow) + m_row.size() * sizeof(uint32_t);
    }

    // The nearest source to q (t's frame) among t's windows, exactly: the least distance
    // over the windows whose wedge holds q. {invalid_id, +inf} when none reaches q.
    struct Nearest {
        uint32_t source = invalid_id;
        double distance = 0;
    };
    Nearest nearest(TriId t, Vec2d q) const;
    // Distance from one source to q (+inf when none of its windows holds q).
    double distance(TriId t, Vec2d q, uint32_t source) const;

  private:
    std::vector<uint32_t> m_row;
    std::vector<SourcedWindow> m_windows;
    size_t m_settled = 0;
};

}  // namespace pelage::sim
