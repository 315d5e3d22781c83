#include "renderer/image_output.h"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

std::string fmt_hash(uint64_t h) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace

uint64_t pixel_hash(const void *data, size_t pixels,
                    const std::vector<std::string> &names,
                    const std::vector<int> &channel_bytes) {
    // FNV-1a, 64 bit, over the stored bytes (half or float), channel by channel in name
    // order: OpenEXR keeps channels sorted, so the order read back may not be the order
    // written.
    const size_t nc = names.size();
    std::vector<size_t> offset(nc, 0), order(nc);
    size_t stride = 0;
    for (size_t c = 0; c < nc; ++c) {
        offset[c] = stride;
        stride += size_t(channel_bytes[c]);
        order[c] = c;
    }
    std::sort(order.begin(), order.end(),
              [&](size_t x, size_t y) { return names[x] < names[y]; });
    uint64_t h = 0xcbf29ce484222325ull;
    const auto *bytes = static_cast<const unsigned char *>(data);
    for (const size_t c : order) {
        for (const char ch : names[c])
            h = (h ^ static_cast<unsigned char>(ch)) * 0x100000001b3ull;
        for (size_t i = 0; i < pixels; ++i) {
            const unsigned char *p = bytes + i * stride + offset[c];
            for (int k = 0; k < channel_bytes[c]; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
        }
    }
    return h;
}

bool exr_is_complete(const std::string &path, std::string *why) {
    auto no = [why](const std::string &reason) {
        if (why) *why = reason;
        return false;
    };
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return no("no file");
    auto in = OIIO::ImageInput::open(path);
    if (!in) return no("unreadable header: " + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    const std::string want = spec.get_string_attribute("pelage:pixel_hash");
    if (want.empty()) return no("no pelage:pixel_hash in the header");
    if (spec.get_int_attribute("pelage:interrupted", 0) != 0)
        return no("an interrupted render");
    // Native per-channel data: exactly the bytes write_exr hashed.
    std::vector<unsigned char> native(spec.image_bytes(true));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, native.data()))
        return no("unreadable pixels: " + in->geterror());
    in->close();
    std::vector<int> sizes(spec.nchannels);
    for (int c = 0; c < spec.nchannels; ++c) sizes[c] = int(spec.channelformat(c).size());
    if (fmt_hash(pixel_hash(native.data(), size_t(spec.width) * spec.height,
                            spec.channelnames, sizes)) != want)
        return no("pixel checksum mismatch");
    return true;
}

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
    if (meta.record_time)
        spec.attribute("pelage:render_seconds", float(meta.render_seconds));
    spec.attribute("pelage:interrupted", int(meta.interrupted));
    if (meta.frame >= 0) spec.attribute("pelage:frame", meta.frame);
    if (meta.fps > 0) spec.attribute("pelage:fps", float(meta.fps));
    if (!meta.record_time) spec.attribute("DateTime", "");  // no capDate: same bytes
    // --- Convert to the stored per-channel types here, so the hash is of those bytes ---
    std::vector<unsigned char> native(spec.image_bytes(true));
    unsigned char *dst = native.data();
    for (size_t i = 0; i < pixels.size(); ++i) {
        if (spec.channelformats[i % nc] == OIIO::TypeDesc::HALF) {
            const uint16_t bits = Imath::half(pixels[i]).bits();
            std::memcpy(dst, &bits, 2);
            dst += 2;
        } else {
            std::memcpy(dst, &pixels[i], 4);
            dst += 4;
        }
    }
    std::vector<int> sizes(nc);
    for (int c = 0; c < nc; ++c) sizes[c] = int(spec.channelformats[c].size());
    spec.attribute(
        "pelage:pixel_hash",
        fmt_hash(pixel_hash(native.data(), size_t(width) * height, names, sizes)));
    write_atomically(path, spec, native.data(), OIIO::TypeDesc::UNKNOWN);
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
    write_rgb8(path, width, height, bytes);
}

void write_rgb8(const std::string &path, int width, int height,
                const std::vector<unsigned char> &rgb) {
    if (rgb.size() != size_t(width) * size_t(height) * 3)
        throw std::logic_error("write_rgb8: pixel count does not match the size");
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "pelage");
    spec.attribute("oiio:ColorSpace", "sRGB");
    write_atomically(path, spec, rgb.data(), OIIO::TypeDesc::UINT8);
}

}  // namespace pelage::renderer
