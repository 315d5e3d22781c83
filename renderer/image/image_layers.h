// The EXR's channels as the scene's film asks for them: the beauty always, then each
// AOV layer that is not switched off, as half or float, the shader's named slots only,
// and the Cryptomatte layers with their metadata.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/image/film.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct ImageLayers {
    int width = 0, height = 0;
    std::vector<std::string> names;  // R G B A first
    std::vector<uint8_t> half;       // per channel: 1 = half, 0 = float
    std::vector<float> pixels;       // interleaved, names.size() per pixel
    // String attributes the layers bring (cryptomatte/<key>/name, ...).
    std::vector<std::pair<std::string, std::string>> attributes;
    int channels() const { return int(names.size()); }
};

// A Cryptomatte layer of the film: its matte name ("object", "type", ...) and how its
// keys are named.
struct CryptomatteSource {
    std::string matte;
    std::function<std::string(uint64_t)> name_of;
};

// `shader_aov_names`: the material plugins' AOV names (unnamed slots are not written).
// `cryptomatte`: one source per layer of the film's Cryptomatte accumulation, in order.
// `denoised`: the denoised beauty (RGB interleaved), written after R G B A as the layer
// `denoised` (denoised_channel is its first channel), or empty.
ImageLayers image_layers(const Film &film, const FilmDesc &desc,
                         const std::vector<std::string> &shader_aov_names,
                         const std::vector<CryptomatteSource> &cryptomatte,
                         const std::function<void(const std::string &)> &warn,
                         const std::vector<float> &denoised = {});
inline constexpr int denoised_channel = 4;

}  // namespace pelage::renderer
