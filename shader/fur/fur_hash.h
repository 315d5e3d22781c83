// Counter-based random numbers for fur: every number is a hash of (seed, strand or
// candidate index, dimension), so strands do not depend on thread count or order.
#pragma once

#include <cstdint>

namespace pelage::fur {

// splitmix64's finalizer (Steele et al. 2014, OOPSLA): a bijective full-avalanche mix.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

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
    const uint64_t h = mix64(mix64(seed ^ (uint64_t(s) * 0x9e3779b97f4a7c15ull)) ^
                             mix64(index * 0xd6e8feb86659fd93ull + dim));
    return double(h >> 11) * 0x1p-53;
}

}  // namespace pelage::fur
