// A minimal PNG writer for debugging views (`pelage preview`): 8-bit RGB, filter 0,
// zlib-compressed. Not for final images, which go through OpenImageIO/OpenColorIO in the
// renderer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pelage::cli {

std::vector<uint8_t> encode_png_rgb8(int width, int height, const std::vector<uint8_t> &rgb);
// Atomic write (sim/atomic_file.h).
void write_png_rgb8(const std::string &path, int width, int height, const std::vector<uint8_t> &rgb);

}  // namespace pelage::cli
