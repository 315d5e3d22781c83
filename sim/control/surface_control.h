// A preset's control (control_spec.h) resolved on the surface a simulation runs on:
// every region's value at every triangle corner, interpolated barycentrically at a
// cell's (triangle, point), so the maps stay attached to the surface.
//
// Values per corner rather than per vertex: a texture seen through UVs can differ on
// either side of a seam, and any/all/not combine corner values (max, min, 1 − x) before
// interpolation. A region is 0 exactly wherever its three corners are 0, which is what
// the mask invariant rests on (a cell where a mask is 0 is never of the masked type).
#pragma once

#include <string>
#include <vector>

#include "sim/control/control_spec.h"
#include "sim/core/random.h"
#include "sim/crps/crps.h"

namespace pelage::sim {

class SurfaceControl {
  public:
    SurfaceControl() = default;
    // Resolves every region of `spec` on `mesh` (the simulated surface) and its CRPS.
    // Attribute and texture regions read `data_mesh` when given (the input, of which
    // `mesh` is a simplified copy without attributes and UVs) and are carried to `mesh`
    // by closest points (corner_transfer.h). InputError (file `preset`, the region's
    // JSON path) when a region needs what the mesh lacks: a vertex attribute, UVs, a
    // readable texture.
    SurfaceControl(const ControlSpec &spec, const TriangleMesh &mesh, const Crps &crps,
                   const std::string &preset, const TriangleMesh *data_mesh = nullptr);

    bool empty() const { return m_spec.empty(); }
    // Points given from now on are in `crps`: the surface resolved on, reshaped (same
    // triangles, e.g. growing, sim/mosaic/growing_surface.h). The values stay on the
    // skin: they live at triangle corners and are read through barycentric coordinates.
    void evaluate_on(const Crps &crps) { m_crps = &crps; }
    const ControlSpec &spec() const { return m_spec; }
    size_t num_regions() const { return m_corner.size(); }

    // Region i's value at corner c of triangle t, and at a point of t (2D frame).
    double corner(int i, TriId t, int c) const { return m_corner[i][3 * size_t(t) + c]; }
    double region(int i, TriId t, Vec2d p) const;
    // A local value at a point: the default moved towards each region's value in turn.
    double value(const LocalValue &v, TriId t, Vec2d p) const;
    // The mean of a local value over a triangle's corners (exact for one region).
    double triangle_mean(const LocalValue &v, TriId t) const;
    // The mask value m at a point: the region (only_in) or one minus it (not_in).
    double mask(const MaskSpec &m, TriId t, Vec2d p) const;

    // The type a cell of type `type` at (t, p) takes after the masks, in order: a mask
    // changes it with probability 1 − m (one number of `rng` per mask that applies), so
    // always where m = 0 (Queiroz §V.A at initialisation and division).
    int draw_masked_type(int type, TriId t, Vec2d p, CounterRng &rng) const;
    // The type after the masks where they are 0 only (after a move: Queiroz's
    // switchCellType for a cell that moved out of its region).
    int masked_type_where_zero(int type, TriId t, Vec2d p) const;

  private:
    ControlSpec m_spec;
    const Crps *m_crps = nullptr;
    std::vector<std::vector<double>> m_corner;  // per region, 3 per triangle
};

}  // namespace pelage::sim
