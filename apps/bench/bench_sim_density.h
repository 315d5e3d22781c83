// The density runs of `pelage bench sim`: one preset on a mesh and on that mesh split at
// its edge midpoints 1 … n times (the same surface with 4^k times the triangles) and on a
// low-poly copy of it (edge collapse to over 100 cells per triangle), each
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
    bool coarse = true;  // and a low-poly copy with > 100 cells per triangle
};

// {"density_mesh", "density_preset", "density": [{subdivisions, triangles,
// simulation_triangles, final_cells, cells_per_triangle, seconds, cell_steps,
// ns_per_cell_step, peak_rss_mb, peak_rss_kb_per_cell}],
// "density_ns_per_cell_step_ratio", "density_peak_rss_ratio", "density_coarse": {the
// same, subdivisions -1}, "density_coarse_ns_per_cell_step_ratio"}: the ratios are the
// finest run's, and the low-poly copy's, over the input's.
nlohmann::json density_runs(const DensityOptions &o);

}  // namespace pelage::renderer::cli
