#include "apps/bench/bench_sim_density.h"

#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "apps/common/common.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/subdivide.h"
#include "sim/remesh/simplify.h"

namespace pelage::renderer::cli {

namespace {

constexpr double coarse_cells_per_triangle = 110;

}  // namespace

nlohmann::json density_runs(const DensityOptions &o) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / fmt::format("pelage-bench-sim-{}", ::getpid());
    fs::create_directories(dir);
    nlohmann::json runs = nlohmann::json::array();
    // One run of `pelage sim` on `mesh`, as the row `level` (-1: the coarse copy).
    auto grow = [&](const sim::TriangleMesh &mesh, int level) {
        const std::string name = level < 0 ? "coarse" : fmt::format("level{}", level);
        const std::string obj = (dir / (name + ".obj")).string();
        const std::string stats = (dir / (name + ".json")).string();
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
        return nlohmann::json{
            {"subdivisions", level},
            {"triangles", s["input_triangles"]},
            {"simulation_triangles", s["triangles"]},
            {"final_cells", s["final_cells"]},
            {"cells_per_triangle", cells / s["triangles"].get<double>()},
            {"seconds", s["seconds"]},
            {"cell_steps", s["cell_steps"]},
            {"ns_per_cell_step", 1e9 * s["seconds"].get<double>() / steps},
            {"peak_rss_mb", s["peak_rss_mb"]},
            {"peak_rss_kb_per_cell", 1024.0 * s["peak_rss_mb"].get<double>() / cells}};
    };
    const sim::TriangleMesh input = sim::load_mesh(o.mesh);
    sim::TriangleMesh mesh = input;
    for (int level = 0; level <= o.levels; ++level) {
        if (level > 0) mesh = sim::subdivide(mesh, sim::Subdivision::midpoint);
        runs.push_back(grow(mesh, level));
    }
    // A low-poly version of the animal: collapsed (no bound on the deviation) to about
    // coarse_cells_per_triangle of the first run's final cells per triangle, the regime
    // of a game-resolution model under a fine pattern.
    nlohmann::json coarse;
    if (o.coarse) {
        const double cells = runs.front()["final_cells"].get<double>();
        const double triangle_area =
            input.surface_area() * coarse_cells_per_triangle / std::max(cells, 1.0);
        const double edge = std::sqrt(4 * triangle_area / std::sqrt(3.0));
        coarse = grow(sim::simplify(input, {edge, 1e30 * edge}), -1);
    }
    fs::remove_all(dir);
    const nlohmann::json &first = runs.front(), &last = runs.back();
    nlohmann::json out = {
        {"density_mesh", o.mesh},
        {"density_preset", o.preset},
        {"density", runs},
        {"density_ns_per_cell_step_ratio", last["ns_per_cell_step"].get<double>() /
                                               first["ns_per_cell_step"].get<double>()},
        {"density_peak_rss_ratio", last["peak_rss_kb_per_cell"].get<double>() /
                                       first["peak_rss_kb_per_cell"].get<double>()}};
    if (!coarse.is_null()) {
        out["density_coarse"] = coarse;
        out["density_coarse_ns_per_cell_step_ratio"] =
            coarse["ns_per_cell_step"].get<double>() /
            first["ns_per_cell_step"].get<double>();
    }
    return out;
}

}  // namespace pelage::renderer::cli
