// A counter-based sampler: every number is a hash of (seed, frame, pixel x, pixel y,
// sample index, dimension), so an image does not depend on thread count or tile order
// (determinism, docs/design.md). No state is shared between pixels.
#pragma once

#include <cstdint>

#include "sim/core/hash.h"

namespace pelage::renderer {

class Sampler {
  public:
    Sampler() = default;  // for arrays of per-pixel streams; assign before use
    Sampler(uint64_t seed, uint32_t frame)
        : m_base(mix64(seed ^ mix64(golden_gamma + frame))) {}

    // Starts the stream of one pixel sample; dimensions restart at 0.
    void start_pixel_sample(uint32_t x, uint32_t y, uint32_t sample) {
        m_key = mix64(m_base ^ mix64((uint64_t(x) << 32 | y) + 0x632be59bd9b4e019ull) ^
                      (uint64_t(sample) * 0xd6e8feb86659fd93ull));
        m_dim = 0;
    }
    // A uniform float in [0, 1).
    float get_1d() {
        const uint64_t h = mix64(m_key + (uint64_t(++m_dim) * golden_gamma));
        return float(h >> 40) * 0x1p-24f;
    }
    // Two uniform floats in [0, 1) from one hash: the top and the next 24 bits of a
    // 64-bit splitmix output are independent to the mix's full avalanche, and one
    // hash per pair halves the sampler's share of the hot loop.
    struct Pair {
        float u1, u2;
    };
    Pair get_2d() {
        const uint64_t h = mix64(m_key + (uint64_t(++m_dim) * golden_gamma));
        return {float(h >> 40) * 0x1p-24f, float((h >> 16) & 0xffffffu) * 0x1p-24f};
    }

  private:
    uint64_t m_base = 0;
    uint64_t m_key = 0;
    uint32_t m_dim = 0;
};

}  // namespace pelage::renderer
