// Every triangle of the simulation surface gets a nearest cell, even on a triangle soup.
//
// Cells live on the surface they were grown on and the closest-cell search walks only
// that surface (geodesics do not jump gaps), so a component that holds no cell has no
// nearest cell: a store mesh exported as thousands of separate pieces, each smaller
// than the cells, would render grey there. Such triangles are carried instead, by
// closest point, onto the triangles that do reach cells (the same closest-point map as
// surface_transfer.h): each keeps the cell-bearing triangles closest to its centroid and
// corners, with the corners' barycentric coordinates in their planes, and a point of it
// takes the first that holds it, else walks across edges from the one it falls most
// inside of. The piece then shows the pattern of the surface it lies on or next to.
// Nothing is carried when no triangle reaches a cell (the mesh holds no cells at all).
#pragma once

#include <cstdint>
#include <vector>

#include "pattern/transfer/surface_transfer.h"
#include "sim/crps/surface.h"

namespace pelage::pattern::transfer {

// What the cover found, for the tools' warnings.
struct CellCoverReport {
    size_t triangles = 0;           // of the simulation surface
    size_t carried_triangles = 0;   // with no cell of their own, carried to one
    size_t carried_pieces = 0;      // connected components among those
    size_t pieces = 0;              // components of the whole surface
    double carried_area_share = 0;  // their share of the surface's area
    double max_carry_distance = 0;  // the farthest corner moved, / bounding-box diagonal
    double without_cell_share = 0;  // area with no cell at all (no cells anywhere)
};

class CellCover {
  public:
    // `reaches[t]`: whether triangle t of `simulation` has cells in reach
    // (ClosestCellIndex::reaches_cells). `simulation` must outlive the cover.
    CellCover(const sim::Surface &simulation, const std::vector<char> &reaches);

    // Whether any triangle is carried (else map() is never needed).
    bool active() const { return !m_slot.empty(); }
    bool carries(sim::TriId t) const { return t < m_slot.size() && m_slot[t] != no_slot; }
    // The cell-bearing triangle and barycentric coordinates for point (b1, b2) of a
    // carried triangle t.
    SurfaceTransfer::Target map(sim::TriId t, float b1, float b2) const;
    const CellCoverReport &report() const { return m_report; }

  private:
    static constexpr uint32_t no_slot = 0xffffffffu;
    struct Candidate {
        sim::TriId tri = sim::invalid_id;
        float b[3][2];  // the carried corners' (b1, b2) in tri
    };
    struct Carried {
        Candidate c[4];
        uint32_t n = 0;
    };
    const sim::Surface *m_surface;
    std::vector<uint32_t> m_slot;  // per triangle: into m_carried, or no_slot
    std::vector<Carried> m_carried;
    CellCoverReport m_report;
};

}  // namespace pelage::pattern::transfer
