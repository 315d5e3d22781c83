#include "apps/common/common.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "renderer/core/install_layout.h"
#include "renderer/core/progress.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {

void ThreadOption::add_to(CLI::App &app) {
    app.add_option("--threads", threads,
                   "Worker threads (0 = all cores); results do not depend on it")
        ->check(CLI::Range(0, 4096));
}

std::unique_ptr<tbb::global_control> ThreadOption::apply() const {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
}

void QuietOption::add_to(CLI::App &app) {
    app.add_flag("-q,--quiet", quiet,
                 "No progress and no summary (errors and warnings are still printed)");
}

void refuse_pattern_seed(CLI::App &app, const std::string &instead) {
    app.add_option_function<std::string>(
           "--seed",
           [instead](const std::string &) {
               throw CLI::ValidationError(
                   "--seed",
                   "is the pattern's seed (sim, look, explore); this "
                   "command's seed is " +
                       instead);
           })
        ->group("");  // hidden from --help
}

bool QuietOption::progress() const {
    return !quiet && renderer::Progress::stderr_is_tty();
}

void StatsJsonOption::add_to(CLI::App &app, const std::string &what) {
    app.add_option("--stats-json", path, "Write " + what + " as JSON to this file")
        ->check(
            [](const std::string &file) -> std::string {
                const std::filesystem::path dir =
                    std::filesystem::absolute(std::filesystem::path(file)).parent_path();
                return std::filesystem::is_directory(dir)
                           ? ""
                           : "\"" + file + "\": folder " + dir.string() +
                                 " does not exist";
            },
            "FILE");
}

void StatsJsonOption::write(const nlohmann::json &j) const {
    if (wanted()) write_json_file(path, j);
}

Resolution parse_resolution(const std::string &text, int max_side, ResolutionForm form,
                            const std::string &field, int min_side) {
    const std::string expected =
        form == ResolutionForm::width_x_height ? "expected WIDTHxHEIGHT, e.g. 1280x720"
        : form == ResolutionForm::square
            ? "expected the side of the square, e.g. 2048 (or 2048x2048)"
            : "expected WIDTHxHEIGHT, e.g. 1280x720, or the longer side, e.g. 800";
    auto refuse = [&](const std::string &why) -> Resolution {
        throw InputError("", 0, field, "\"" + text + "\": " + why);
    };
    Resolution r;
    int w = 0, h = 0, used = 0;
    if (std::sscanf(text.c_str(), "%dx%d%n", &w, &h, &used) == 2 &&
        size_t(used) == text.size()) {
        r.width = w;
        r.height = h;
    } else if (form != ResolutionForm::width_x_height &&
               std::sscanf(text.c_str(), "%d%n", &w, &used) == 1 &&
               size_t(used) == text.size()) {
        r.width = r.height = w;
        r.longer_side_only = true;
    } else {
        return refuse(expected);
    }
    if (std::min(r.width, r.height) < min_side || std::max(r.width, r.height) > max_side)
        return refuse("each side must be in [" + std::to_string(min_side) + ", " +
                      std::to_string(max_side) + "]");
    if (form == ResolutionForm::square && r.width != r.height)
        return refuse("the image is square; " + expected);
    return r;
}

void parse_resolution(const std::string &text, int max_side, int *width, int *height) {
    const Resolution r =
        parse_resolution(text, max_side, ResolutionForm::width_x_height, "--res");
    *width = r.width;
    *height = r.height;
}

void write_json_file(const std::string &path, const nlohmann::json &j) {
    write_file_atomically(path, [&](std::ostream &out) { out << j.dump(2) << "\n"; });
}

std::string data_path(const std::string &relative) { return find_data(relative); }

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;  // Linux reports KiB
}

double process_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string shell_quoted(const std::string &s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string self_path() {
    return std::filesystem::read_symlink("/proc/self/exe").string();
}

}  // namespace pelage::renderer::cli
