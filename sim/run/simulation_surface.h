// The surface `pelage sim` and `pelage bench sim` grow a pattern on: the input mesh, or a
// copy simplified to the scale of the cells the preset is expected to end with
// (sim/remesh/cell_scale_surface.h). The initial cell count is taken from the input, so
// both surfaces give the same pattern scale.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "sim/crps/surface.h"
#include "sim/mosaic/preset.h"
#include "sim/remesh/cell_scale_surface.h"

namespace pelage::sim {

class SimulationSurface {
  public:
    // `cells` > 0 overrides the preset's initial count; `simplify` false keeps the input.
    // The input is released once a simplified copy stands for it: a dense mesh would
    // otherwise weigh on the whole run; its mesh (without CRPS) stays when the preset's
    // regions read vertex attributes or UVs (sim/control).
    // InputError naming mesh_path when the run would not fit in memory. `phase` is told
    // of the remeshing step (setup_step.h).
    SimulationSurface(Surface input, const std::string &mesh_path, const Preset &preset,
                      uint64_t cells, bool simplify,
                      const std::function<void(const std::string &)> &phase = {});
    const sim::Surface &surface() const {
        return m_simplified ? *m_simplified : *m_input;
    }
    uint64_t initial_cells() const { return m_initial; }
    // The mesh carrying the input's attributes and UVs: the input's when kept.
    const sim::TriangleMesh &data_mesh() const {
        return m_input_mesh ? *m_input_mesh : surface().mesh;
    }
    const sim::CellScaleReport &report() const { return m_report; }

  private:
    std::optional<sim::Surface> m_input;
    std::optional<sim::Surface> m_simplified;
    std::optional<sim::TriangleMesh> m_input_mesh;
    uint64_t m_initial = 0;
    sim::CellScaleReport m_report;
};

}  // namespace pelage::sim
