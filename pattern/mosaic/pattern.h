// A simulated mosaic ready for lookups: the .cells file, the surface it was grown on and
// the closest-cell index. The mesh given is the one rendered: when it is the one the
// cells were grown on (its hash), or the same triangles in the same order with their
// corners within round-off of the file's (its vertices shared otherwise, as in a rig's
// unwelded rest pose), lookups take its triangles directly; when it is another mesh of
// the same shape, the simulation surface is rebuilt from the file and transfer()
// carries the render mesh's points onto it (surface_transfer.h). The
// clonal_mosaic plugin (and through it the colour under every fur root), `pelage
// lookup` and `pelage bake` all go through this one class, so every tool sees exactly
// the renderer's pattern.
//
// Every point has a cell: simulation triangles on a component that holds none (the
// pieces of a triangle soup) are carried to the closest cell-bearing surface
// (cell_cover.h); locate() composes that with the transfer, and cover() reports it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "pattern/mosaic/closest_cell.h"
#include "pattern/transfer/cell_cover.h"
#include "pattern/transfer/surface_transfer.h"
#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"

namespace pelage::pattern::mosaic {

class MosaicPattern {
  public:
    // Throws pelage::InputError for an unreadable or corrupt .cells file or a mesh that
    // is not the shape the cells were grown on.
    MosaicPattern(const std::string &cells_path, const std::string &mesh_path,
                  Neighbourhood neighbourhood = Neighbourhood::geodesic);
    // The same for a render mesh already loaded (sim/mesh/mesh_load.h) — the renderer's,
    // handed to the plugin; `render_name` names it in messages.
    MosaicPattern(const std::string &cells_path, sim::TriangleMesh render,
                  const std::string &render_name,
                  Neighbourhood neighbourhood = Neighbourhood::geodesic);
    // On the surface the .cells file carries (the one it was grown on): for tools that
    // measure the pattern itself, with no render mesh at hand (`pelage stats`, `sim`).
    explicit MosaicPattern(const std::string &cells_path,
                           Neighbourhood neighbourhood = Neighbourhood::geodesic);

    // Triangles of the simulation surface (what the index and cells refer to).
    size_t num_triangles() const { return m_cells.num_triangles(); }
    // The map from the render mesh to the simulation surface; null when they are one.
    const transfer::SurfaceTransfer *transfer() const { return m_transfer.get(); }
    // Carries the simulation triangles that reach no cell to ones that do; inactive
    // (nothing carried) on a surface whose every component holds cells.
    const transfer::CellCover &cover() const { return *m_cover; }
    // The simulation triangle and barycentric point whose nearest cell colours point
    // (b1, b2) of render triangle t: through the transfer, then the cover. A t beyond
    // the render mesh's triangles is returned as it is.
    transfer::SurfaceTransfer::Target locate(uint32_t t, float b1, float b2) const {
        transfer::SurfaceTransfer::Target at{t, b1, b2};
        if (m_transfer && t < m_transfer->num_render_triangles())
            at = m_transfer->map(t, b1, b2);
        if (m_cover->carries(at.tri)) at = m_cover->map(at.tri, at.b1, at.b2);
        return at;
    }
    // Local CRPS coordinates of barycentric point (b1, b2) of triangle t.
    Vec2f point(sim::TriId t, float b1, float b2) const {
        const float *f = &m_tri[6 * size_t(t)];
        return {f[0] + b1 * f[2] + b2 * f[4], f[1] + b1 * f[3] + b2 * f[5]};
    }
    const ClosestCellIndex &index() const { return *m_index; }
    const CellTable &cells() const { return m_cells; }
    const std::vector<sim::CellsFileType> &types() const { return m_data.types; }
    const sim::CellsData &data() const { return m_data; }
    const sim::Surface &surface() const { return *m_surface; }  // the simulation's

  private:
    // The cell table, closest-cell index and triangle frames of m_data on m_surface.
    void index_cells(Neighbourhood neighbourhood);

    sim::CellsData m_data;
    std::unique_ptr<sim::Surface> m_surface;
    CellTable m_cells;
    std::unique_ptr<ClosestCellIndex> m_index;
    std::unique_ptr<transfer::SurfaceTransfer> m_transfer;
    std::unique_ptr<transfer::CellCover> m_cover;
    std::vector<float>
        m_tri;  // per triangle: v0 (2), e1 (2), e2 (2), local CRPS coordinates
};

}  // namespace pelage::pattern::mosaic
