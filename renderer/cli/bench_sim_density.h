// The density runs of `pelage bench sim`: one preset on a mesh and on that mesh split at
// its edge midpoints 1 … n times (the same surface with 4^k times the triangles), each
// grown by a separate `pelage sim` process so that its peak memory is its own. What a
// user pays per cell should not depend on how finely the mesh was tessellated.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace pelage::renderer::cli {

struct DensityOptions {
    std::string mesh;    // the coarsest mesh
    std::string preset;  // name or file
    int levels = 2;      // subdivisions of the finest run
    uint64_t seed = 1;
    int threads = 0;
};

// {"density_mesh", "density_preset", "density": [{subdivisions, triangles,
// simulation_triangles, final_cells, seconds, cell_steps, ns_per_cell_step, peak_rss_mb,
// peak_rss_kb_per_cell}], "density_ns_per_cell_step_ratio", "density_peak_rss_ratio"}:
// the ratios are the finest run's over the coarsest.
nlohmann::json density_runs(const DensityOptions &o);

}  // namespace pelage::renderer::cli
