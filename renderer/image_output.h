// Writing renders through OpenImageIO, always atomically (a temporary file in the
// destination folder, renamed into place once complete).
//   * EXR: one part, channel-prefixed layers (Film::channel_names: R G B A, albedo.*,
//   N.*,
//     depth.Z, id.*, shader.*), colour layers half or float, depth/ids/shader always
//     float, ZIP compression, metadata pelage:scene, pelage:spp, pelage:seed,
//     pelage:render_seconds, pelage:interrupted, Software = "pelage <version>".
//   * PNG/JPEG preview: the beauty through an OCIO display transform, 8 bits per channel.
#pragma once

#include <string>
#include <vector>

#include "renderer/color_management.h"
#include "renderer/film.h"

namespace pelage::renderer {

struct ImageMetadata {
    std::string scene, software;
    int spp = 0;
    unsigned long long seed = 0;
    double render_seconds = 0;
    bool interrupted = false;
};

// `pixels`: Film::num_channels interleaved floats per pixel (Film::resolve()).
void write_exr(const std::string &path, int width, int height,
               const std::vector<float> &pixels,
               const std::vector<std::string> &channel_names, bool half,
               const ImageMetadata &meta);

// The first three channels of `pixels` (stride `channels`) through `display`, as 8-bit
// RGB.
void write_preview(const std::string &path, int width, int height,
                   const std::vector<float> &pixels, int channels,
                   const DisplayTransform &display);

}  // namespace pelage::renderer
