#include "renderer/core/install_layout.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace pelage::renderer {

namespace fs = std::filesystem;

std::string executable_dir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.parent_path().string();
}

std::string code_file() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void *>(&code_file), &info) && info.dli_fname)
        return fs::absolute(info.dli_fname).string();
    return "";
}

namespace {

// The folders relative to bin/ come from the install folders CMake was configured with
// (CMakeLists.txt: PELAGE_PKGLIBDIR, PELAGE_PKGDATADIR).
std::string next_to_executable(const char *relative) {
    const std::string dir = executable_dir();
    return dir.empty() ? dir : (fs::path(dir) / relative).lexically_normal().string();
}

}  // namespace

std::string package_lib_dir() { return next_to_executable(PELAGE_PKGLIBDIR_FROM_BINDIR); }

std::string package_data_dir() {
    return next_to_executable(PELAGE_PKGDATADIR_FROM_BINDIR);
}

std::string find_data(const std::string &relative) {
    std::vector<fs::path> candidates;
    if (const char *dir = std::getenv("PELAGE_DATA_DIR"); dir && *dir)
        candidates.push_back(fs::path(dir) / relative);
    if (const std::string dir = package_data_dir(); !dir.empty())
        candidates.push_back(fs::path(dir) / relative);
    if (candidates.empty()) return relative;
    for (const fs::path &p : candidates) {
        std::error_code ec;
        if (fs::exists(p, ec)) return p.string();
    }
    return candidates.front().string();
}

}  // namespace pelage::renderer
