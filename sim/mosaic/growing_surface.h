// The surface a Clonal Mosaic grows on (Walter thesis §6.2, Fig. 6.1): the simulation
// surface's shape at the current age, as a CRPS whose address stays put, so a
// CmSimulation built on crps() sees every reshape. Cells keep their (triangle,
// barycentric) point across a reshape: the pattern rides on the surface (thesis §6.7).
#pragma once

#include <vector>

#include "sim/crps/crps.h"
#include "sim/growth/growth_shape.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"

namespace pelage::sim {

class GrowingSurface {
  public:
    // `rest`: the simulation surface's mesh at rest (the one a pattern is written on),
    // with its CRPS; `shape` resolved on its vertices (resolve_growth). Starts at
    // shape.first_age().
    GrowingSurface(const TriangleMesh &rest, const Crps &rest_crps, GrowthShape shape);
    GrowingSurface(const GrowingSurface &) = delete;
    GrowingSurface &operator=(const GrowingSurface &) = delete;

    const Crps &crps() const { return m_crps; }
    const TriangleMesh &mesh() const { return m_mesh; }
    const GrowthShape &shape() const { return m_shape; }
    // The CRPS of the rest shape, built on demand: what a preset's regions and fields
    // are resolved on (their box-space points and body axis mean the rest pose).
    Crps rest_crps() const;
    double age() const { return m_age; }
    // Takes the shape at `age` and carries every cell to its barycentric point on it.
    void reshape(double age, Cells &cells);
    // The area of every triangle in the shape at `age`.
    std::vector<double> triangle_areas(double age) const;

  private:
    TriangleMesh m_mesh;
    std::vector<Vec3d> m_rest_positions;
    Crps m_crps;
    GrowthShape m_shape;
    double m_age = 0;
};

// Moves every cell from its point in `from` to the point with the same barycentric
// coordinates in `to` (two CRPS of one topology): the same triangle, no new bucket order.
void carry_cells(const Crps &from, const Crps &to, Cells &cells);

// Walter thesis §6.2 (L1470–1516), per triangle: with a = A0/N0 the area of one cell,
// a triangle whose area grows by ΔA over the next interval gains ΔN = ΔA/a cells, split
// between its cell types by relative rates g_i ∝ 1/division_time_i: k = ΔN / Σ N_i g_i,
// ΔN_i = k N_i g_i, so every cell of type i divides k·g_i times on average over the
// interval (r_i = Δt N_i / ΔN_i between divisions). No division where ΔA ≤ 0.
// Deviation, for triangles smaller than a cell: a triangle without a dividing cell hands
// its ΔN to the dividing cells of its neighbours (edge or vertex), split the same way;
// with none there either it is lost (counted in *lost, in cells).
// `cell_rates`, when given, holds each cell's g instead of its type's (a local
// division_time, read where the cell stands: Queiroz §V).
// Returns each cell's expected number of divisions over the interval.
std::vector<double> growth_divisions(const Crps &crps, const Cells &cells,
                                     const CellTypes &types,
                                     const std::vector<double> &area_now,
                                     const std::vector<double> &area_next,
                                     double cell_area, double *lost,
                                     const std::vector<double> *cell_rates = nullptr);

// One update of a growing run: the time, the surface's area and the cells on it.
struct GrowthSample {
    double time = 0, area = 0;
    size_t cells = 0;
};

}  // namespace pelage::sim
