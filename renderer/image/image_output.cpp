#include "renderer/image/image_output.h"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>
#define XXH_INLINE_ALL  // header-only: the hash inlines into its loop
#include <xxhash.h>

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

namespace {

// The byte offset of each channel in a packed pixel, and the pixel's size.
size_t channel_offsets(const std::vector<int> &channel_bytes,
                       std::vector<size_t> &offset) {
    offset.assign(channel_bytes.size(), 0);
    size_t stride = 0;
    for (size_t c = 0; c < channel_bytes.size(); ++c) {
        offset[c] = stride;
        stride += size_t(channel_bytes[c]);
    }
    return stride;
}

// Channel indices in name order: OpenEXR keeps channels sorted, so the order read back
// may not be the order written.
std::vector<size_t> name_order(const std::vector<std::string> &names) {
    std::vector<size_t> order(names.size());
    for (size_t c = 0; c < order.size(); ++c) order[c] = c;
    std::sort(order.begin(), order.end(),
              [&](size_t x, size_t y) { return names[x] < names[y]; });
    return order;
}

// The checksum of older files, those that carry pelage:pixel_hash: FNV-1a 64 over each
// channel's name and bytes, in name order. Read only, so that --resume still recognises
// their finished frames; byte by byte, slow, but only such files pay for it.
uint64_t legacy_fnv_pixel_hash(const void *data, size_t pixels,
                               const std::vector<std::string> &names,
                               const std::vector<int> &channel_bytes) {
    std::vector<size_t> offset;
    const size_t stride = channel_offsets(channel_bytes, offset);
    uint64_t h = 0xcbf29ce484222325ull;
    const auto *bytes = static_cast<const unsigned char *>(data);
    for (const size_t c : name_order(names)) {
        for (const char ch : names[c])
            h = (h ^ static_cast<unsigned char>(ch)) * 0x100000001b3ull;
        for (size_t i = 0; i < pixels; ++i) {
            const unsigned char *p = bytes + i * stride + offset[c];
            for (int k = 0; k < channel_bytes[c]; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
        }
    }
    return h;
}

}  // namespace

uint64_t pixel_hash(const void *data, size_t pixels,
                    const std::vector<std::string> &names,
                    const std::vector<int> &channel_bytes) {
    // XXH3-64 of each channel's bytes in pixel order, then XXH3-64 over (name, NUL,
    // that digest as 8 little-endian bytes) for every channel in name order. One pass
    // over the packed pixels: runs of pixels are split into per-channel buffers while
    // they are in cache.
    std::vector<size_t> offset;
    const size_t stride = channel_offsets(channel_bytes, offset);
    const size_t nc = names.size();
    std::vector<XXH3_state_t> state(nc);
    for (XXH3_state_t &st : state) XXH3_64bits_reset(&st);
    const auto *bytes = static_cast<const unsigned char *>(data);
    constexpr size_t run = 1024;  // pixels per pass: a run's bytes stay in L1/L2
    std::vector<unsigned char> channel(run * 8);
    for (size_t i0 = 0; i0 < pixels; i0 += run) {
        const size_t n = std::min(run, pixels - i0);
        for (size_t c = 0; c < nc; ++c) {
            const size_t b = size_t(channel_bytes[c]);
            if (b * run > channel.size()) channel.resize(b * run);
            const unsigned char *p = bytes + i0 * stride + offset[c];
            // Fixed sizes let the copies compile to single moves.
            if (b == 2)
                for (size_t i = 0; i < n; ++i)
                    std::memcpy(&channel[2 * i], p + i * stride, 2);
            else if (b == 4)
                for (size_t i = 0; i < n; ++i)
                    std::memcpy(&channel[4 * i], p + i * stride, 4);
            else
                for (size_t i = 0; i < n; ++i)
                    std::memcpy(&channel[b * i], p + i * stride, b);
            XXH3_64bits_update(&state[c], channel.data(), n * b);
        }
    }
    XXH3_state_t all;
    XXH3_64bits_reset(&all);
    for (const size_t c : name_order(names)) {
        XXH3_64bits_update(&all, names[c].c_str(), names[c].size() + 1);
        const uint64_t d = XXH3_64bits_digest(&state[c]);
        unsigned char le[8];
        for (int k = 0; k < 8; ++k) le[k] = static_cast<unsigned char>(d >> (8 * k));
        XXH3_64bits_update(&all, le, sizeof le);
    }
    return XXH3_64bits_digest(&all);
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
    // pelage:pixel_xxh3, or pelage:pixel_hash (FNV-1a) in older files.
    std::string want = spec.get_string_attribute("pelage:pixel_xxh3");
    const bool legacy = want.empty();
    if (legacy) want = spec.get_string_attribute("pelage:pixel_hash");
    if (want.empty()) return no("no pelage:pixel_xxh3 in the header");
    if (spec.get_int_attribute("pelage:interrupted", 0) != 0)
        return no("an interrupted render");
    // Native per-channel data: exactly the bytes write_exr hashed.
    std::vector<unsigned char> native(spec.image_bytes(true));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, native.data()))
        return no("unreadable pixels: " + in->geterror());
    in->close();
    std::vector<int> sizes(spec.nchannels);
    for (int c = 0; c < spec.nchannels; ++c) sizes[c] = int(spec.channelformat(c).size());
    const size_t pixels = size_t(spec.width) * spec.height;
    if (fmt_hash(
            legacy
                ? legacy_fnv_pixel_hash(native.data(), pixels, spec.channelnames, sizes)
                : pixel_hash(native.data(), pixels, spec.channelnames, sizes)) != want)
        return no("pixel checksum mismatch");
    return true;
}

void write_exr(const std::string &path, int width, int height,
               const std::vector<float> &pixels, const std::vector<std::string> &names,
               bool half, const ImageMetadata &meta) {
    ImageLayers layers;
    layers.width = width;
    layers.height = height;
    layers.names = names;
    for (const std::string &n : names) {
        // Depth, ids and plugin values need float precision (ids above 2048 are not exact
        // in half); colour layers use the requested type.
        const bool exact = n.rfind("depth.", 0) == 0 || n.rfind("id.", 0) == 0 ||
                           n.rfind("shader.", 0) == 0;
        layers.half.push_back(half && !exact);
    }
    layers.pixels = pixels;
    write_exr(path, layers, meta);
}

void write_exr(const std::string &path, const ImageLayers &layers,
               const ImageMetadata &meta) {
    const int width = layers.width, height = layers.height;
    const std::vector<std::string> &names = layers.names;
    const std::vector<float> &pixels = layers.pixels;
    const int nc = int(names.size());
    OIIO::ImageSpec spec(width, height, nc, OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.alpha_channel = 3;
    spec.z_channel = -1;
    spec.channelformats.resize(nc);
    for (int c = 0; c < nc; ++c)
        spec.channelformats[c] =
            layers.half[size_t(c)] ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    spec.attribute("compression", meta.compression);
    spec.attribute("Software", meta.software);
    spec.attribute("pelage:scene", meta.scene);
    spec.attribute("pelage:spp", meta.spp);
    spec.attribute("pelage:seed", std::to_string(meta.seed));
    if (meta.clamp_indirect > 0)
        spec.attribute("pelage:clamp_indirect", meta.clamp_indirect);
    if (meta.fur_bounce_roughness > 0)
        spec.attribute("pelage:fur_bounce_roughness", meta.fur_bounce_roughness);
    if (meta.noise_threshold > 0) {
        spec.attribute("pelage:noise_threshold", meta.noise_threshold);
        spec.attribute("pelage:min_spp", meta.min_spp);
        spec.attribute("pelage:mean_spp", float(meta.mean_spp));
    }
    if (meta.record_time)
        spec.attribute("pelage:render_seconds", float(meta.render_seconds));
    spec.attribute("pelage:interrupted", int(meta.interrupted));
    if (meta.frame >= 0) spec.attribute("pelage:frame", meta.frame);
    if (meta.fps > 0) {
        spec.attribute("pelage:fps", float(meta.fps));
        // OpenEXR's framesPerSecond, a rational: 24 → 24/1, 29.97 → 29970/1000.
        const int den = std::abs(meta.fps - std::round(meta.fps)) < 1e-6 ? 1 : 1000;
        const int rational[2] = {int(std::lround(meta.fps * den)), den};
        spec.attribute("FramesPerSecond", OIIO::TypeRational, rational);
    }
    if (meta.world_to_camera)
        spec.attribute("worldtocamera", OIIO::TypeMatrix, meta.world_to_camera->data());
    if (meta.world_to_ndc)
        spec.attribute("worldtoNDC", OIIO::TypeMatrix, meta.world_to_ndc->data());
    for (const auto &[k, v] : meta.strings) spec.attribute(k, v);
    for (const auto &[k, v] : layers.attributes) spec.attribute(k, v);
    for (const auto &[k, v] : meta.ints) spec.attribute(k, v);
    if (!meta.view.empty()) spec.attribute("pelage:view", meta.view);
    if (!meta.settings_xxh3.empty())
        spec.attribute("pelage:settings_xxh3", meta.settings_xxh3);
    if (meta.full_width > 0) {
        spec.x = meta.x;
        spec.y = meta.y;
        spec.full_width = meta.full_width;
        spec.full_height = meta.full_height;
    }
    if (!meta.record_time) spec.attribute("DateTime", "");  // no capDate: same bytes
    // --- Convert to the stored per-channel types here, so the hash is of those bytes ---
    std::vector<unsigned char> native(spec.image_bytes(true));
    if (pixels.size() != size_t(width) * height * nc)
        throw std::invalid_argument(path + ": write_exr: pixel buffer size mismatch");
    std::vector<uint8_t> to_half(nc);
    for (int c = 0; c < nc; ++c)
        to_half[c] = spec.channelformats[c] == OIIO::TypeDesc::HALF;
    unsigned char *dst = native.data();
    const float *src = pixels.data();
    for (size_t p = 0; p < size_t(width) * height; ++p)  // pixel by pixel: no i % nc
        for (int c = 0; c < nc; ++c, ++src) {
            if (to_half[c]) {
                const uint16_t bits = Imath::half(*src).bits();
                std::memcpy(dst, &bits, 2);
                dst += 2;
            } else {
                std::memcpy(dst, src, 4);
                dst += 4;
            }
        }
    std::vector<int> sizes(nc);
    for (int c = 0; c < nc; ++c) sizes[c] = int(spec.channelformats[c].size());
    spec.attribute(
        "pelage:pixel_xxh3",
        fmt_hash(pixel_hash(native.data(), size_t(width) * height, names, sizes)));
    write_atomically(path, spec, native.data(), OIIO::TypeDesc::UNKNOWN);
}

void write_preview(const std::string &path, int width, int height,
                   const std::vector<float> &pixels, int channels,
                   const DisplayTransform &display, int first) {
    std::vector<float> rgb(size_t(width) * height * 3);
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = pixels[i * channels + first + c];
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
