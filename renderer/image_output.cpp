#include "renderer/image_output.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace pelage::renderer {

namespace fs = std::filesystem;

namespace {

// A temporary name in the destination's folder, keeping the extension (OIIO picks the
// format by it).
std::string temp_name(const std::string &path) {
    const fs::path p(path);
    return (p.parent_path() / ("." + p.stem().string() + ".tmp" +
                               std::to_string(getpid()) + p.extension().string()))
        .string();
}

void write_atomically(const std::string &path, const OIIO::ImageSpec &spec,
                      const void *data, OIIO::TypeDesc format) {
    const std::string tmp = temp_name(path);
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        throw std::runtime_error(path +
                                 ": cannot write this image format: " + OIIO::geterror());
    bool ok = out->open(tmp, spec) && out->write_image(format, data);
    ok = out->close() && ok;
    if (!ok) {
        const std::string e = out->geterror();
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write image: " + e);
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(
            path + ": cannot move the finished image into place: " + ec.message());
    }
}

}  // namespace

void write_exr(const std::string &path, int width, int height,
               const std::vector<float> &pixels, const std::vector<std::string> &names,
               bool half, const ImageMetadata &meta) {
    const int nc = int(names.size());
    OIIO::ImageSpec spec(width, height, nc,
                         half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.alpha_channel = 3;
    spec.z_channel = -1;
    spec.channelformats.resize(nc);
    for (int c = 0; c < nc; ++c) {
        // Depth, ids and plugin values need float precision (ids above 2048 are not exact
        // in half); colour layers use the requested type.
        const bool exact = names[c].rfind("depth.", 0) == 0 ||
                           names[c].rfind("id.", 0) == 0 ||
                           names[c].rfind("shader.", 0) == 0;
        spec.channelformats[c] =
            exact || !half ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF;
    }
    spec.attribute("compression", "zip");
    spec.attribute("Software", meta.software);
    spec.attribute("pelage:scene", meta.scene);
    spec.attribute("pelage:spp", meta.spp);
    spec.attribute("pelage:seed", std::to_string(meta.seed));
    spec.attribute("pelage:render_seconds", float(meta.render_seconds));
    spec.attribute("pelage:interrupted", int(meta.interrupted));
    write_atomically(path, spec, pixels.data(), OIIO::TypeDesc::FLOAT);
}

void write_preview(const std::string &path, int width, int height,
                   const std::vector<float> &pixels, int channels,
                   const DisplayTransform &display) {
    std::vector<float> rgb(size_t(width) * height * 3);
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = pixels[i * channels + c];
    display.apply_rgb(rgb.data(), size_t(width) * height);
    std::vector<unsigned char> bytes(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) {
        const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
        bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "pelage");
    spec.attribute("oiio:ColorSpace", "sRGB");
    write_atomically(path, spec, bytes.data(), OIIO::TypeDesc::UINT8);
}

}  // namespace pelage::renderer
