#include "apps/bench/bench_sim_mclone.h"

#include <fmt/core.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "apps/common/common.h"
#include "sim/run/grow_cells.h"

namespace pelage::renderer::cli {

namespace {

// MClone (Walter's program) on this configuration and the cow, global relaxation, on
// the project's 2-core reference machine: 30.6 CPU s.
constexpr double mclone_cpu_seconds = 30.6;
constexpr uint64_t initial_cells = 16000;

// Walter thesis Fig. 3.10 (GI98 Table 2, the cheetah): ρ 18, w_r 2, 15 days, division
// times 8 (F) and 60 (B), α_FF 0.8; α_BB 0.5, w_d 0.067 and w_a 0 after Queiroz et al.;
// P(F) 0.15; Poisson division delays. Built on the shipped walter-cheetah preset so the
// colours and names are its own.
nlohmann::json mclone_preset() {
    nlohmann::json p;
    std::ifstream(data_path("scenes/presets/walter-cheetah.json")) >> p;
    p["name"] = "mclone-cheetah";
    p["types"][0]["initial_probability"] = 0.15;
    p["types"][1]["initial_probability"] = 0.85;
    p["adhesion"] = {{0.8, 0.0}, {0.0, 0.5}};
    nlohmann::json &s = p["simulation"];
    s["initial_cells"] = initial_cells;
    s["w_r"] = 2.0;
    s["w_d"] = 0.067;
    s["w_a"] = 0.0;
    s.erase("anisotropy");
    s["rho"] = 18;
    s["end_time"] = 15;
    s["division_distribution"] = "poisson";
    return p;
}

}  // namespace

nlohmann::json mclone_runs(const McloneOptions &o) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / fmt::format("pelage-bench-mclone-{}", ::getpid());
    fs::create_directories(dir);
    nlohmann::json runs = nlohmann::json::array();
    for (const char *mode : {"local", "global"}) {
        nlohmann::json preset = mclone_preset();
        preset["simulation"]["relax"] = mode;
        const std::string file = (dir / fmt::format("mclone-{}.json", mode)).string();
        std::ofstream(file) << preset.dump(1);
        nlohmann::json best;
        for (int k = 0; k < o.repeat; ++k) {
            sim::GrowRequest request;
            request.mesh = o.mesh;
            request.preset = file;
            request.preset_dir = data_path("scenes/presets");
            request.seed = o.seed;
            // What a `pelage sim` run does, from loading the mesh to the .cells data
            // (MClone's figure is its whole run too).
            const double cpu0 = process_cpu_seconds();
            const Timer timer;
            const sim::GrownCells grown = sim::grow_cells(request);
            const double cpu = process_cpu_seconds() - cpu0, wall = timer.seconds();
            const double steps = std::max<double>(1, double(grown.stats.cell_steps));
            if (k == 0 || cpu < best["cpu_seconds"].get<double>())
                best = {{"relax", mode},
                        {"cpu_seconds", cpu},
                        {"seconds", wall},
                        {"final_cells", grown.data.num_cells()},
                        {"cell_steps", grown.stats.cell_steps},
                        {"ns_per_cell_step", 1e9 * cpu / steps},
                        {"seconds_force_sum", grown.stats.seconds_force_sum},
                        {"interacting_pairs", grown.stats.interacting_pairs},
                        {"speedup", mclone_cpu_seconds / cpu}};
        }
        runs.push_back(best);
    }
    fs::remove_all(dir);
    return {{"mclone",
             {{"mesh", o.mesh},
              {"initial_cells", initial_cells},
              {"mclone_cpu_seconds", mclone_cpu_seconds},
              {"runs", runs}}}};
}

}  // namespace pelage::renderer::cli
