// Baked textures as other tools read them: linear colour encoded as 8-bit sRGB (the
// colour space glTF's baseColorTexture and UsdUVTexture's "sRGB" expect), in PNG.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer {

// Linear colour to the sRGB encoding (IEC 61966-2-1), clamped to [0, 1], rounded.
unsigned char srgb8(float linear);

// The first three of `channels` floats per texel, `texels` texels, as sRGB bytes.
std::vector<unsigned char> srgb_rgb8(const std::vector<float> &pixels, int channels,
                                     size_t texels);

// The PNG file's bytes of an RGB8 image (written through OpenImageIO and read back).
std::string png_bytes(int width, int height, const std::vector<unsigned char> &rgb,
                      const std::string &scratch_path);

}  // namespace pelage::renderer
