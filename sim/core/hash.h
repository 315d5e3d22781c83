// The one 64-bit integer mixer behind every counter-based random stream in pelage (the
// simulation's CounterRng, the renderer's Sampler, the fur layer's uniform()): SplitMix64
// (Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom Number Generators", OOPSLA).
// Its finaliser is a bijection with full avalanche, so hashing a combination of counters
// gives independent-looking numbers without any shared state (docs/design.md,
// "Determinism").
#pragma once

#include <cstdint>

namespace pelage {

// SplitMix64's golden-ratio increment, 2^64 / φ rounded to odd.
inline constexpr uint64_t golden_gamma = 0x9e3779b97f4a7c15ull;

// SplitMix64's output finaliser (Stafford's "Mix13" variant of MurmurHash3's fmix64).
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// One full SplitMix64 step from state z: advance by the golden gamma, then finalise.
constexpr uint64_t splitmix64(uint64_t z) { return mix64(z + golden_gamma); }

}  // namespace pelage
