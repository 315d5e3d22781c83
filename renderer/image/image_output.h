// Writing renders through OpenImageIO, always atomically (a temporary file in the
// destination folder, renamed into place once complete).
//   * EXR: one part, channel-prefixed layers (Film::channel_names: R G B A, albedo.*,
//   N.*,
//     depth.Z, id.*, shader.*), colour layers half or float, depth/ids/shader always
//     float, ZIP compression, metadata pelage:scene, pelage:spp, pelage:seed,
//     pelage:render_seconds, pelage:interrupted, pelage:view, Software = "pelage
//     <version>".
//   * PNG/JPEG preview: the beauty through an OCIO display transform, 8 bits per channel.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/image/color_management.h"
#include "renderer/image/film.h"
#include "renderer/image/image_layers.h"

namespace pelage::renderer {

struct ImageMetadata {
    std::string scene, software;
    int spp = 0;
    unsigned long long seed = 0;
    double render_seconds = 0;
    bool interrupted = false;
    int frame = -1;  // animation frame (pelage:frame), -1 = a still
    // Adaptive sampling (pelage:noise_threshold, pelage:min_spp, pelage:mean_spp); 0 =
    // off, nothing written.
    float noise_threshold = 0;
    float clamp_indirect = 0;  // pelage:clamp_indirect when on
    // pelage:fur_bounce_roughness when a furry scene regularises its paths (biased, as
    // clamping is); 0 = not written.
    float fur_bounce_roughness = 0;
    int min_spp = 0;
    double mean_spp = 0;
    double fps = 0;  // animation.fps (pelage:fps), 0 = none
    // The OpenColorIO view the render is meant for (pelage:view), "" = none.
    std::string view{};
    // pelage:settings_xxh3: the hash of everything that determines the pixels, so that
    // --resume and `pelage merge` trust only output of the same settings; "" = none.
    std::string settings_xxh3;
    // A tile (`pelage render --tile`): the pixels are the data window at (x, y) of a
    // display window full_width × full_height (OpenEXR's convention); 0 = the image.
    int x = 0, y = 0, full_width = 0, full_height = 0;
    bool record_time =
        true;  // false: no pelage:render_seconds, so that the same frame
               // rendered twice (another machine, --resume) is the same file
    // OpenEXR's standard worldToCamera and worldToNDC (Camera::world_to_camera()).
    std::optional<std::array<float, 16>> world_to_camera, world_to_ndc;
    std::string compression = "zip";  // OpenEXR compression (OIIO's name)
    // Further attributes: render settings (pelage:*) and the layers' own
    // (cryptomatte/<key>/...).
    std::vector<std::pair<std::string, std::string>> strings;
    std::vector<std::pair<std::string, int>> ints;
};

// A checksum of the pixels as the EXR stores them (`data`: packed pixels, each channel
// `channel_bytes` wide), independent of channel order (XXH3-64 per channel, then over
// the names and digests in name order), written as pelage:pixel_xxh3, so a frame can
// be checked complete (--resume).
uint64_t pixel_hash(const void *data, size_t pixels,
                    const std::vector<std::string> &names,
                    const std::vector<int> &channel_bytes);

// True when `path` is an EXR pelage wrote completely: the header reads, every pixel
// reads, and the pixels hash to pelage:pixel_xxh3 (or, in older files, to
// pelage:pixel_hash, FNV-1a). Otherwise false with the reason.
bool exr_is_complete(const std::string &path, std::string *why = nullptr);

// The layers as image_layers() chose them, each channel half or float as it says.
void write_exr(const std::string &path, const ImageLayers &layers,
               const ImageMetadata &meta);

// `pixels`: interleaved floats, one per name; colour layers half when `half`, depth,
// ids and shader values float.
void write_exr(const std::string &path, int width, int height,
               const std::vector<float> &pixels,
               const std::vector<std::string> &channel_names, bool half,
               const ImageMetadata &meta);

// Three channels of `pixels` (stride `channels`) from `first` on through `display`, as
// 8-bit RGB.
void write_preview(const std::string &path, int width, int height,
                   const std::vector<float> &pixels, int channels,
                   const DisplayTransform &display, int first = 0);

// Already display-referred 8-bit RGB (e.g. `pelage preview`), in the format the
// extension names (PNG, JPEG, …), sRGB-tagged.
void write_rgb8(const std::string &path, int width, int height,
                const std::vector<unsigned char> &rgb);

}  // namespace pelage::renderer
