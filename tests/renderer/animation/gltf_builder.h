// Writing small glTF 2.0 documents in tests: each add() is one bufferView and one
// accessor of the document's one buffer, embedded as a data: URI.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pelage::test {

using json = nlohmann::json;

inline std::string base64(const std::string &bytes) {
    static const char *abc =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 |
                           uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += abc[(v >> s) & 63];
    }
    if (i < bytes.size()) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += abc[(v >> 18) & 63];
        out += abc[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? abc[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// Builds a glTF document's one buffer: each add() is one bufferView and one accessor.
struct GltfBuilder {
    json doc = {{"asset", {{"version", "2.0"}}}};
    std::string bin;
    int add(const std::vector<float> &v, const char *type, bool minmax = false) {
        return add_raw(
            std::string(reinterpret_cast<const char *>(v.data()), 4 * v.size()), 5126,
            type,
            v.size() / (std::strcmp(type, "SCALAR") == 0 ? 1
                        : std::strcmp(type, "VEC3") == 0 ? 3
                        : std::strcmp(type, "VEC4") == 0 ? 4
                        : std::strcmp(type, "MAT4") == 0 ? 16
                                                         : 2),
            minmax ? &v : nullptr);
    }
    int add_u16(const std::vector<uint16_t> &v, const char *type, size_t count) {
        return add_raw(
            std::string(reinterpret_cast<const char *>(v.data()), 2 * v.size()), 5123,
            type, count, nullptr);
    }
    int add_raw(const std::string &bytes, int component, const char *type, size_t count,
                const std::vector<float> *positions) {
        while (bin.size() % 4) bin.push_back('\0');
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
        bin += bytes;
        json a = {{"bufferView", doc["bufferViews"].size() - 1},
                  {"componentType", component},
                  {"count", count},
                  {"type", type}};
        if (positions) {
            std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
            for (size_t i = 0; i < positions->size(); ++i)
                lo[i % 3] = std::min(lo[i % 3], (*positions)[i]),
                       hi[i % 3] = std::max(hi[i % 3], (*positions)[i]);
            a["min"] = lo;
            a["max"] = hi;
        }
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size() - 1);
    }
    std::string text() {
        doc["buffers"] = json::array(
            {{{"byteLength", bin.size()},
              {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        return doc.dump();
    }
};

}  // namespace pelage::test
