// Counter-based random numbers: every draw is a pure function of (seed, stream, index),
// so a result never depends on which thread asked for it or in what order
// (docs/design.md, "Determinism"). Each counter passes through a full SplitMix64 step
// (sim/core/hash.h) before it is combined with the next.
#pragma once

#include <cmath>
#include <cstdint>

#include "sim/core/hash.h"

namespace pelage::sim {

constexpr uint64_t hash_counters(uint64_t seed, uint64_t stream, uint64_t index) {
    return splitmix64(splitmix64(splitmix64(seed) ^ stream) ^ index);
}

// Named streams, so two uses of the same index never share numbers.
enum class RandomStream : uint64_t {
    initial_position = 1,
    initial_type = 2,
    initial_division = 3,
    division = 4,
    tie_break = 5,
    growth_division = 6,
    local_type = 7,     // initial types from local probabilities (sim/control)
    mask_initial = 8,   // neural-crest masks at initialisation
    mask_division = 9,  // ... on a child
    mask_switch = 10,   // the division time of a cell a mask switched
};

// A small sequential generator over one (seed, stream, index) key: each draw hashes the
// next sub-counter. Cheap to create, no state shared between keys.
class CounterRng {
  public:
    CounterRng(uint64_t seed, RandomStream stream, uint64_t index)
        : m_key(hash_counters(seed, static_cast<uint64_t>(stream), index)) {}

    uint64_t next_u64() {
        return splitmix64(m_key + 0x632be59bd9b4e019ull * ++m_counter);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next_u64() >> 11) * 0x1.0p-53; }
    // Uniform in (0, 1]: safe under log().
    double uniform_open0() { return 1.0 - uniform(); }

    // Exponential deviate with the given mean (inter-arrival time of a Poisson process).
    double exponential(double mean) { return -mean * std::log(uniform_open0()); }

    // Poisson deviate with the given mean by inversion of the CDF (O(mean) work; the
    // means used here are division times of at most a few hundred time units). Above
    // 500, where e^-mean nears underflow, a rounded normal approximation is used.
    uint64_t poisson(double mean) {
        if (mean <= 0) return 0;
        if (mean > 500) {
            const double u1 = uniform_open0(), u2 = uniform();
            const double n =
                std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
            const double v = std::floor(mean + std::sqrt(mean) * n + 0.5);
            return v < 0 ? 0 : static_cast<uint64_t>(v);
        }
        const double u = uniform();
        double p = std::exp(-mean), cdf = p;
        uint64_t k = 0;
        while (u > cdf && k < 100000) {
            ++k;
            p *= mean / double(k);
            cdf += p;
            if (p == 0 && double(k) > mean) break;  // rounding left cdf just below u
        }
        return k;
    }

  private:
    uint64_t m_key;
    uint64_t m_counter = 0;
};

}  // namespace pelage::sim
