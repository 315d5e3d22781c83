// The mesh readers take a path (they size their allocations from the file size), so the
// mesh fuzz targets hand them the input through a scratch file, one per process.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace pelage::fuzz {

// Writes `data` to a per-process file with extension `ext` and returns its path. The file
// lives in /dev/shm when there is one (no disk traffic at thousands of runs per second).
inline const std::string &write_input_file(const uint8_t *data, size_t size,
                                           const std::string &ext) {
    static const std::string path = [&] {
        const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                              ? "/dev/shm"
                                              : std::filesystem::temp_directory_path();
        return (dir / ("pelage_fuzz_" + std::to_string(getpid()) + ext)).string();
    }();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data), std::streamsize(size));
    return path;
}

}  // namespace pelage::fuzz
