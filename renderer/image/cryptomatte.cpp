#include "renderer/image/cryptomatte.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <unordered_map>

namespace pelage::renderer {

namespace {

uint32_t rotl32(uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }

uint32_t fmix32(uint32_t h) {
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

}  // namespace

uint32_t murmur3_32(std::string_view data, uint32_t seed) {
    constexpr uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
    const size_t n = data.size(), blocks = n / 4;
    const auto *bytes = reinterpret_cast<const unsigned char *>(data.data());
    uint32_t h = seed;
    for (size_t i = 0; i < blocks; ++i) {
        // Little-endian blocks, as the reference on x86 reads them.
        uint32_t k = uint32_t(bytes[4 * i]) | uint32_t(bytes[4 * i + 1]) << 8 |
                     uint32_t(bytes[4 * i + 2]) << 16 | uint32_t(bytes[4 * i + 3]) << 24;
        k *= c1;
        k = rotl32(k, 15);
        k *= c2;
        h ^= k;
        h = rotl32(h, 13);
        h = h * 5 + 0xe6546b64u;
    }
    const unsigned char *tail = bytes + 4 * blocks;
    uint32_t k = 0;
    switch (n & 3) {
        case 3:
            k ^= uint32_t(tail[2]) << 16;
            [[fallthrough]];
        case 2:
            k ^= uint32_t(tail[1]) << 8;
            [[fallthrough]];
        case 1:
            k ^= tail[0];
            k *= c1;
            k = rotl32(k, 15);
            k *= c2;
            h ^= k;
    }
    h ^= uint32_t(n);
    return fmix32(h);
}

uint32_t cryptomatte_hash(std::string_view name) {
    uint32_t h = murmur3_32(name);
    // An exponent of 0 (denormal) or 255 (inf, NaN) flips its lowest bit: such ids
    // would not survive image operations that flush denormals or test for NaN.
    const uint32_t exponent = h >> 23 & 255u;
    if (exponent == 0 || exponent == 255) h ^= 1u << 23;
    return h;
}

float cryptomatte_id(uint32_t hash) {
    float f;
    std::memcpy(&f, &hash, sizeof f);
    return f;
}

std::string cryptomatte_key(std::string_view layer_name) {
    return fmt::format("{:08x}", murmur3_32(layer_name)).substr(0, 7);
}

std::string cryptomatte_layer_name(const std::string &matte) {
    std::string n = matte;
    if (!n.empty()) n[0] = char(std::toupper(static_cast<unsigned char>(n[0])));
    return "Crypto" + n;
}

CryptomatteFilm::CryptomatteFilm(int width, int height, int layers, int slots)
    : m_width(width),
      m_height(height),
      m_layers(layers),
      m_slots(slots),
      m_keys(size_t(width) * height * layers * slots, no_key),
      m_weights(size_t(width) * height * layers * slots, 0.0f) {}

std::vector<CryptomatteFilm::Entry> CryptomatteFilm::ranked(int x, int y,
                                                            int layer) const {
    const size_t base =
        (size_t(y) * m_width + x) * m_layers * m_slots + size_t(layer) * m_slots;
    std::vector<Entry> e;
    for (int s = 0; s < m_slots && m_keys[base + s] != no_key; ++s)
        e.push_back({m_keys[base + s], m_weights[base + s]});
    std::sort(e.begin(), e.end(), [](const Entry &a, const Entry &b) {
        return a.weight != b.weight ? a.weight > b.weight : a.key < b.key;
    });
    return e;
}

CryptomatteLayer resolve_cryptomatte(
    const CryptomatteFilm &film, int layer, const std::string &name, int ranks, int width,
    int height, const std::function<float(int, int)> &total_weight,
    const std::function<std::string(uint64_t)> &name_of,
    const std::function<void(const std::string &)> &warn) {
    CryptomatteLayer out;
    out.name = name;
    const int images = (ranks + 1) / 2;  // two ranks per RGBA image
    for (int i = 0; i < images; ++i)
        for (const char *c : {"R", "G", "B", "A"})
            out.channels.push_back(fmt::format("{}{:02d}.{}", name, i, c));
    out.planes.assign(out.channels.size(),
                      std::vector<float>(size_t(width) * height, 0.0f));

    // Each key's id, hashed once; the names go to the manifest.
    std::unordered_map<uint64_t, float> id_of;
    std::map<std::string, uint32_t> manifest;  // sorted: the same bytes every run
    std::unordered_map<uint32_t, std::string> seen;
    auto id = [&](uint64_t key) {
        if (auto it = id_of.find(key); it != id_of.end()) return it->second;
        const std::string n = name_of(key);
        const uint32_t h = cryptomatte_hash(n);
        if (auto s = seen.find(h); s != seen.end() && s->second != n)
            warn("Cryptomatte " + name + ": \"" + n + "\" and \"" + s->second +
                 "\" hash to the same id; their mattes are one");
        seen.emplace(h, n);
        manifest.emplace(n, h);
        return id_of.emplace(key, cryptomatte_id(h)).first->second;
    };

    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float total = total_weight(x, y);
            if (!(total > 0)) continue;
            const auto entries = film.ranked(x, y, layer);
            const size_t p = size_t(y) * width + x;
            for (int r = 0; r < ranks && r < int(entries.size()); ++r) {
                out.planes[size_t(2 * r)][p] = id(entries[size_t(r)].key);
                out.planes[size_t(2 * r + 1)][p] = entries[size_t(r)].weight / total;
            }
        }
    nlohmann::json m = nlohmann::json::object();
    for (const auto &[n, h] : manifest) m[n] = fmt::format("{:08x}", h);
    out.manifest = m.dump();
    return out;
}

}  // namespace pelage::renderer
