#include "renderer/cli/common.h"

#include <sys/resource.h>

#include <cstdio>

#include "renderer/core/install_layout.h"
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

void parse_resolution(const std::string &text, int max_side, int *width, int *height) {
    int w = 0, h = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 1 || h < 1 ||
        w > max_side || h > max_side)
        throw InputError("", 0, "--res",
                         "\"" + text + "\": expected WIDTHxHEIGHT, e.g. 1280x720");
    *width = w;
    *height = h;
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

}  // namespace pelage::renderer::cli
