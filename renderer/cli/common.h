// Pieces every subcommand shares: how a subcommand is registered, the --threads and
// --stats-json options, locating the project's data, timing.
#pragma once

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace pelage::renderer::cli {

// A subcommand registers its options on `app` and returns what runs once parsing
// succeeded; it returns the exit code (0 ok, 1 runtime failure). Bad input is thrown as
// pelage::InputError and turned into exit code 2 by main().
using Runner = std::function<int()>;

Runner add_crps_command(CLI::App &app);
Runner add_bench_command(CLI::App &app);
Runner add_sim_command(CLI::App &app);
Runner add_stats_command(CLI::App &app);
Runner add_preview_command(CLI::App &app);

Runner add_render_command(CLI::App &app);
Runner add_shaders_command(CLI::App &app);
Runner add_compare_command(CLI::App &app);
Runner add_cells_command(CLI::App &app);
Runner add_lookup_command(CLI::App &app);
Runner add_bake_command(CLI::App &app);
Runner add_movie_command(CLI::App &app);
Runner add_matte_command(CLI::App &app);
Runner add_merge_command(CLI::App &app);

// --threads N (0 = all cores). Keep the returned control alive while working.
struct ThreadOption {
    int threads = 0;
    void add_to(CLI::App &app);
    std::unique_ptr<tbb::global_control> apply() const;
};

// "1280x720" -> width, height; InputError at field "--res" otherwise.
void parse_resolution(const std::string &text, int max_side, int *width, int *height);

// Writes `j` to `path` atomically (pretty-printed, trailing newline).
void write_json_file(const std::string &path, const nlohmann::json &j);

// Resolves a path inside pelage's data (scenes/...): $PELAGE_DATA_DIR first, then
// share/pelage next to the executable (renderer/core/install_layout.h).
std::string data_path(const std::string &relative);

// The process's peak resident memory so far, in MB.
double peak_rss_mb();

// CPU time of the whole process (all threads), seconds. Unlike wall time it is not
// inflated when other jobs share the machine: benchmarks report work per busy core.
double process_cpu_seconds();

class Timer {
  public:
    Timer() : m_start(std::chrono::steady_clock::now()) {}
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start)
            .count();
    }

  private:
    std::chrono::steady_clock::time_point m_start;
};

}  // namespace pelage::renderer::cli
