// Pieces every subcommand shares: how a subcommand is registered, the options every
// command spells the same way (--threads, -q/--quiet, --stats-json, --res), locating
// the project's data, timing.
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
Runner add_fields_command(CLI::App &app);
Runner add_presets_command(CLI::App &app);
Runner add_info_command(CLI::App &app);
Runner add_compare_command(CLI::App &app);
Runner add_cells_command(CLI::App &app);
Runner add_lookup_command(CLI::App &app);
Runner add_bake_command(CLI::App &app);
Runner add_movie_command(CLI::App &app);
Runner add_matte_command(CLI::App &app);
Runner add_merge_command(CLI::App &app);
Runner add_look_command(CLI::App &app);
Runner add_export_command(CLI::App &app);
Runner add_explore_command(CLI::App &app);

// --threads N (0 = all cores). Keep the returned control alive while working.
struct ThreadOption {
    int threads = 0;
    void add_to(CLI::App &app);
    std::unique_ptr<tbb::global_control> apply() const;
};

// -q/--quiet: no progress bar and no summary; errors and warnings are still printed.
struct QuietOption {
    bool quiet = false;
    void add_to(CLI::App &app);
    explicit operator bool() const { return quiet; }
    // Whether a progress bar is drawn: not quiet, and stderr is a terminal.
    bool progress() const;
};

// --seed is the pattern's seed on every command that grows one (sim, look, explore,
// bench sim, bench fur-colour). A command whose seed is another one's, its sampler's
// (--sampler-seed) or its random points' (--points-seed), refuses --seed as the command
// line is read, naming the option it takes instead, so that an old script is told and
// not silently rendered with another meaning.
void refuse_pattern_seed(CLI::App &app, const std::string &instead);

// --stats-json FILE: what the command measured, as one JSON object written atomically.
// Its keys are each command's contract (listed at the top of its cmd_*.cpp). A FILE in a
// missing folder is refused when the command line is read, before any work.
struct StatsJsonOption {
    std::string path;
    void add_to(CLI::App &app, const std::string &what);
    bool wanted() const { return !path.empty(); }
    void write(const nlohmann::json &j) const;  // nothing without --stats-json
};

// --res, the one resolution syntax: WIDTHxHEIGHT on every command. Where the image's
// shape is the command's own (a preview takes the mesh's, an atlas is square), one
// number N is accepted too: the longer side, the side of a square.
struct Resolution {
    int width = 0, height = 0;
    bool longer_side_only = false;  // N alone: width = height = N
};
enum class ResolutionForm { width_x_height, or_longer_side, square };
// Throws InputError at `field` for anything else, a side outside [min_side, max_side],
// and, for `square`, unequal sides.
Resolution parse_resolution(const std::string &text, int max_side, ResolutionForm form,
                            const std::string &field = "--res", int min_side = 1);
// "1280x720" into a film's width and height.
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

// `s` in single quotes for /bin/sh (a ' inside becomes '\''), for the child `pelage`
// processes benchmarks start.
std::string shell_quoted(const std::string &s);

// This very binary (/proc/self/exe), so child runs measure the code being benchmarked.
std::string self_path();

}  // namespace pelage::renderer::cli
