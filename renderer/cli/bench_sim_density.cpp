#include "renderer/cli/bench_sim_density.h"

#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "renderer/cli/common.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/subdivide.h"

namespace pelage::renderer::cli {

nlohmann::json density_runs(const DensityOptions &o) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / fmt::format("pelage-bench-sim-{}", ::getpid());
    fs::create_directories(dir);
    nlohmann::json runs = nlohmann::json::array();
    sim::TriangleMesh mesh = sim::load_mesh(o.mesh);
    for (int level = 0; level <= o.levels; ++level) {
        if (level > 0) mesh = sim::subdivide(mesh, sim::Subdivision::midpoint);
        const std::string obj = (dir / fmt::format("level{}.obj", level)).string();
        const std::string stats = (dir / fmt::format("level{}.json", level)).string();
        sim::write_obj(obj, mesh, {});
        const std::string command = fmt::format(
            "{} sim --mesh {} --preset {} --seed {} --threads {} --stats-json {} "
            ">/dev/null",
            shell_quoted(self_path()), shell_quoted(obj), shell_quoted(o.preset), o.seed,
            o.threads, shell_quoted(stats));
        if (std::system(command.c_str()) != 0) {
            fs::remove_all(dir);
            throw std::runtime_error("bench sim: `" + command + "` failed");
        }
        nlohmann::json s;
        std::ifstream(stats) >> s;
        const double steps = std::max(1.0, s["cell_steps"].get<double>());
        const double cells = std::max(1.0, s["final_cells"].get<double>());
        runs.push_back(
            {{"subdivisions", level},
             {"triangles", s["input_triangles"]},
             {"simulation_triangles", s["triangles"]},
             {"final_cells", s["final_cells"]},
             {"seconds", s["seconds"]},
             {"cell_steps", s["cell_steps"]},
             {"ns_per_cell_step", 1e9 * s["seconds"].get<double>() / steps},
             {"peak_rss_mb", s["peak_rss_mb"]},
             {"peak_rss_kb_per_cell", 1024.0 * s["peak_rss_mb"].get<double>() / cells}});
    }
    fs::remove_all(dir);
    const nlohmann::json &first = runs.front(), &last = runs.back();
    return {
        {"density_mesh", o.mesh},
        {"density_preset", o.preset},
        {"density", runs},
        {"density_ns_per_cell_step_ratio", last["ns_per_cell_step"].get<double>() /
                                               first["ns_per_cell_step"].get<double>()},
        {"density_peak_rss_ratio", last["peak_rss_kb_per_cell"].get<double>() /
                                       first["peak_rss_kb_per_cell"].get<double>()}};
}

}  // namespace pelage::renderer::cli
