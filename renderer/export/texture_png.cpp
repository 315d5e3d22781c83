#include "renderer/export/texture_png.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "renderer/image/image_output.h"

namespace pelage::renderer {

unsigned char srgb8(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    const float e =
        c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
    return static_cast<unsigned char>(std::lround(e * 255));
}

std::vector<unsigned char> srgb_rgb8(const std::vector<float> &pixels, int channels,
                                     size_t texels) {
    std::vector<unsigned char> rgb(3 * texels);
    for (size_t p = 0; p < texels; ++p)
        for (size_t k = 0; k < 3; ++k)
            rgb[3 * p + k] = srgb8(pixels[size_t(channels) * p + k]);
    return rgb;
}

std::string png_bytes(int width, int height, const std::vector<unsigned char> &rgb,
                      const std::string &scratch_path) {
    write_rgb8(scratch_path, width, height, rgb);
    std::ifstream in(scratch_path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    in.close();
    std::error_code ec;
    std::filesystem::remove(scratch_path, ec);
    if (bytes.str().empty())
        throw std::runtime_error(scratch_path + ": the PNG could not be read back");
    return bytes.str();
}

}  // namespace pelage::renderer
