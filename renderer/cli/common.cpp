#include "renderer/cli/common.h"

#include <cstdio>
#include <cstdlib>
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

}  // namespace pelage::cli
