#include "sim/run/simulation_surface.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "sim/mosaic/cm_simulation.h"
#include "sim/mosaic/final_cells.h"
#include "sim/mosaic/preset.h"
#include "sim/run/setup_step.h"

namespace pelage::sim {

SimulationSurface::SimulationSurface(
    sim::Surface input_surface, const std::string &mesh_path, const sim::Preset &preset,
    uint64_t cells, bool simplify, const std::function<void(const std::string &)> &phase)
    : m_input(std::move(input_surface)) {
    const sim::Surface &input = *m_input;
    m_initial = cells > 0 ? cells : sim::initial_cell_count(preset.params, input.crps);
    double area = 0;
    for (sim::TriId t = 0; t < input.crps.num_triangles(); ++t)
        area += input.crps.frame(t).area;
    sim::CellScaleRequest request;
    request.area = area;
    request.expected_cells =
        sim::expected_final_cells(preset.params, preset.types, m_initial);
    // r = w_r·sqrt(A/m) (Walter 1998 §3.3) at the initial count, widened as the
    // relaxation's cache is; the largest local w_r (sim/control).
    request.neighbourhood_radius =
        sim::Neighbourhoods::slack * preset.control.w_r.max() *
        std::sqrt(area / double(std::max<uint64_t>(m_initial, 1)));
    m_report = sim::plan_cell_scale(input.mesh, request);
    if (!simplify) {
        m_report.simplified = false;
        m_report.refine_levels = 0;
        m_report.output_triangles = m_report.input_triangles;
    }
    // Refused up front rather than run out of memory: three quarters of the machine's
    // memory, or of the address space the process may use when that is limited.
    double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        available = std::min(available, double(limit.rlim_cur));
    if (available > 0)
        sim::check_neighbourhood_memory(m_report, 0.75 * available, mesh_path);
    if (!m_report.remeshed()) return;
    // The input's CRPS and topology go before the remeshing's own structures come.
    const SetupStep step(phase, "remeshing to the cells' scale");
    sim::TriangleMesh mesh = std::move(m_input->mesh);
    m_input.reset();
    m_simplified.emplace(sim::build_surface(sim::remesh_to_cell_scale(mesh, &m_report)));
    // A coarsening that kept no copy leaves the input, with the input's neighbourhoods.
    if (!m_report.remeshed() && available > 0)
        sim::check_neighbourhood_memory(m_report, 0.75 * available, mesh_path);
    if (preset.control.needs_mesh_data()) m_input_mesh = std::move(mesh);
}

}  // namespace pelage::sim
