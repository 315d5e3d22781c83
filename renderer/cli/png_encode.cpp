#include "renderer/cli/png_encode.h"

#include <array>
#include <ostream>
#include <stdexcept>

#include <zlib.h>

#include "sim/atomic_file.h"

namespace pelage::cli {

namespace {

// CRC-32 of the PNG specification (ISO/IEC 15948 Annex D).
uint32_t crc32(const uint8_t *p, size_t n, uint32_t c = 0xffffffffu) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t v = i;
            for (int k = 0; k < 8; ++k) v = (v & 1) ? 0xedb88320u ^ (v >> 1) : v >> 1;
            t[i] = v;
        }
        return t;
    }();
    for (size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c;
}

void put_be32(std::vector<uint8_t> &out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void put_chunk(std::vector<uint8_t> &out, const char type[4], const std::vector<uint8_t> &data) {
    put_be32(out, static_cast<uint32_t>(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put_be32(out, crc32(out.data() + start, out.size() - start) ^ 0xffffffffu);
}

}  // namespace

std::vector<uint8_t> encode_png_rgb8(int width, int height, const std::vector<uint8_t> &rgb) {
    // --- Raw scanlines, filter type 0 ---
    std::vector<uint8_t> raw;
    raw.reserve(size_t(height) * (size_t(width) * 3 + 1));
    for (int y = 0; y < height; ++y) {
        raw.push_back(0);
        raw.insert(raw.end(), rgb.begin() + size_t(y) * width * 3, rgb.begin() + size_t(y + 1) * width * 3);
    }
    // --- zlib stream (RFC 1950), best compression ---
    uLongf z_size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<uint8_t> z(z_size);
    if (compress2(z.data(), &z_size, raw.data(), static_cast<uLong>(raw.size()), 9) != Z_OK)
        throw std::runtime_error("PNG: zlib compression failed");
    z.resize(z_size);

    std::vector<uint8_t> out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> ihdr;
    put_be32(ihdr, static_cast<uint32_t>(width));
    put_be32(ihdr, static_cast<uint32_t>(height));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, filter 0, no interlace
    put_chunk(out, "IHDR", ihdr);
    put_chunk(out, "IDAT", z);
    put_chunk(out, "IEND", {});
    return out;
}

void write_png_rgb8(const std::string &path, int width, int height, const std::vector<uint8_t> &rgb) {
    const std::vector<uint8_t> bytes = encode_png_rgb8(width, height, rgb);
    write_file_atomically(path, [&](std::ostream &out) {
        out.write(reinterpret_cast<const char *>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace pelage::cli
