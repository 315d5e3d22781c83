// `pelage stats FILE.cells [--json]`: pattern statistics of a .cells file
// (sim/cells_io/pattern_stats.h). JSON keys are a contract: cells_by_type, spot_fraction,
// spots, mean_spot_area.
#include <fmt/core.h>

#include <iostream>

#include "renderer/cli/common.h"
#include "sim/cells_io/cells_file.h"
#include "sim/cells_io/pattern_stats.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer::cli {
namespace {

struct StatsOptions {
    std::string file, stats_json, mesh;
    bool json = false;
};

int run_stats(const StatsOptions &o) {
    const sim::CellsData data = sim::read_cells_file(o.file);
    if (!o.mesh.empty())
        sim::check_cells_match_mesh(data, sim::load_mesh(o.mesh), o.file);
    const sim::PatternStats s = sim::compute_pattern_stats(data);
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto &[name, n] : s.cells_by_type) by_type[name] = n;
    const nlohmann::json j = {
        {"file", o.file},
        {"triangles", data.num_triangles()},
        {"area", s.area},
        {"cells", s.total_cells},
        {"cells_by_type", by_type},
        {"spot_fraction", s.spot_fraction},
        {"spots", s.spots},
        {"mean_spot_area", s.mean_spot_area},
        {"largest_spot_cells", s.largest_spot_cells},
    };
    if (!o.stats_json.empty()) write_json_file(o.stats_json, j);
    if (o.json) {
        std::cout << j.dump(2) << std::endl;
    } else {
        fmt::print("pelage stats: {}\n", o.file);
        fmt::print("  triangles {}  area {:.6g}  cells {}  {}\n", data.num_triangles(),
                   s.area, s.total_cells, by_type.dump());
        fmt::print("  spot fraction {:.4f}  spots {}  mean spot area {:.4g}\n",
                   s.spot_fraction, s.spots, s.mean_spot_area);
    }
    return 0;
}

}  // namespace

Runner add_stats_command(CLI::App &app) {
    auto o = std::make_shared<StatsOptions>();
    CLI::App *sub = app.add_subcommand("stats", "Pattern statistics of a .cells file");
    sub->add_option("file", o->file, ".cells file")->required();
    sub->add_flag("--json", o->json, "Print JSON on stdout");
    sub->add_option("--mesh", o->mesh,
                    "Also check that the cells were made for this mesh");
    sub->add_option("--stats-json", o->stats_json, "Also write the JSON to this file");
    return [o] { return run_stats(*o); };
}

}  // namespace pelage::renderer::cli
