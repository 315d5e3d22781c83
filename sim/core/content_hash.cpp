#include "sim/core/content_hash.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cstdio>
#include <fstream>
#include <vector>

namespace pelage {

struct ContentHash::State {
    XXH3_state_t xxh;
};

ContentHash::ContentHash() : m_state(std::make_unique<State>()) {
    XXH3_64bits_reset(&m_state->xxh);
}

ContentHash::~ContentHash() = default;

void ContentHash::add(const std::string &text) {
    XXH3_64bits_update(&m_state->xxh, text.c_str(), text.size() + 1);
}

void ContentHash::add_file(const std::string &path) {
    add(path);
    std::ifstream in(path, std::ios::binary);
    std::vector<char> buf(1 << 16);
    while (in) {
        in.read(buf.data(), std::streamsize(buf.size()));
        XXH3_64bits_update(&m_state->xxh, buf.data(), size_t(in.gcount()));
    }
}

uint64_t ContentHash::digest() const { return XXH3_64bits_digest(&m_state->xxh); }

std::string ContentHash::hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(digest()));
    return buf;
}

}  // namespace pelage
