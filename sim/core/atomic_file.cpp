#include "sim/core/atomic_file.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace pelage {

void write_file_atomically(const std::string &path,
                           const std::function<void(std::ostream &)> &write) {
    namespace fs = std::filesystem;
    const fs::path final_path(path);
    fs::path tmp = final_path;
    tmp += ".tmp." + std::to_string(::getpid());
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) throw std::runtime_error(path + ": cannot open for writing");
            write(out);
            out.flush();
            if (!out) throw std::runtime_error(path + ": write failed");
        }
        std::error_code ec;
        fs::rename(tmp, final_path, ec);
        if (ec)
            throw std::runtime_error(path + ": cannot move into place: " + ec.message());
    } catch (...) {
        std::error_code ignore;
        fs::remove(tmp, ignore);
        throw;
    }
}

}  // namespace pelage
