// Counter-based random numbers for fur: every number is a hash of (seed, strand or
// candidate index, dimension), so strands do not depend on thread count or order.
#pragma once

#include <cstdint>

#include "sim/core/hash.h"

namespace pelage::renderer {

// Random streams of the fur layer (one per purpose, so adding a dimension to one never
// shifts another).
enum class Stream : uint64_t {
    roots = 1,
    thinning = 2,
    shape = 3,
    pigment = 4,
    guides = 5
};

// A uniform double in [0, 1) for (seed, stream, index, dim).
inline double uniform(uint64_t seed, Stream s, uint64_t index, uint32_t dim) {
    const uint64_t h = mix64(mix64(seed ^ (uint64_t(s) * golden_gamma)) ^
                             mix64(index * 0xd6e8feb86659fd93ull + dim));
    return double(h >> 11) * 0x1p-53;
}

}  // namespace pelage::renderer
