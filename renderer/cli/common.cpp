#include "renderer/cli/common.h"

#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>

#include "sim/atomic_file.h"

namespace pelage::cli {

void ThreadOption::add_to(CLI::App &app) {
    app.add_option("--threads", threads, "Worker threads (0 = all cores); results do not depend on it")
        ->check(CLI::Range(0, 4096));
}

std::unique_ptr<tbb::global_control> ThreadOption::apply() const {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<size_t>(threads));
}

void write_json_file(const std::string &path, const nlohmann::json &j) {
    write_file_atomically(path, [&](std::ostream &out) { out << j.dump(2) << "\n"; });
}

std::string data_path(const std::string &relative) {
    if (const char *dir = std::getenv("PELAGE_DATA_DIR"); dir && *dir)
        return (std::filesystem::path(dir) / relative).string();
    return (std::filesystem::path(PELAGE_SOURCE_DIR) / relative).string();
}

Progress::Progress(std::string label) : m_label(std::move(label)), m_tty(isatty(fileno(stderr)) != 0) {}

Progress::~Progress() {
    if (m_tty && m_last >= 0) std::fprintf(stderr, "\n");
}

void Progress::update(double fraction) {
    if (!m_tty) return;
    const int percent = static_cast<int>(fraction * 100);
    if (percent == m_last) return;
    m_last = percent;
    const int filled = percent * 30 / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", m_label.c_str(), filled,
                 "##############################", 30 - filled, "", percent);
    std::fflush(stderr);
}

}  // namespace pelage::cli
