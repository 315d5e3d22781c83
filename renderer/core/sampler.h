// The sampler: every number is a function of (seed, frame, pixel x, pixel y, sample
// index, dimension) alone, so an image does not depend on thread count or tile order
// (determinism, docs/design.md). No state is shared between pixels.
//
// Two kinds:
//  * sobol (the default): shuffled, Owen-scrambled Sobol points, padded by dimension
//    pairs (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4), §4–5; the
//    scheme of pbrt-v4's PaddedSobolSampler). Each get_2d() is the pixel's own scrambled
//    copy of Sobol's first two dimensions, so the samples 0..2^k − 1 of a pixel form a
//    (0, 2)-net in every pair: stratified in each 1D and 2D projection, whatever the
//    spp's power of two. The sample index is shuffled by a nested uniform scramble per
//    pair (which maps aligned blocks of 2^k indices onto aligned blocks), so pairs do not
//    correlate with each other, and each coordinate is Owen-scrambled with its own seed.
//    The render's passes of 1, 1, 2, 4, ... samples end on powers of two.
//  * independent: a hash per number (uniform white noise), for comparison.
#pragma once

#include <cstdint>

#include "sim/core/hash.h"

namespace pelage::renderer {

namespace sobol_detail {

constexpr uint32_t reverse_bits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    return __builtin_bswap32(x);
}

// Burley 2020 §3 (after Laine & Karras 2011, with Burley's constants): a hash in which
// each bit depends only on itself and lower bits, i.e. an Owen scramble of the reversed
// bits.
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// Owen scrambling of a 32-bit fraction whose bits are given reversed (`rx`): each bit
// flipped by a hash of the bits above it, the result in normal order. Callers keep
// values reversed where they can, which saves a reversal per scramble.
constexpr uint32_t owen_scramble_reversed(uint32_t rx, uint32_t seed) {
    return reverse_bits(laine_karras_permutation(rx, seed));
}

// Sobol's second dimension with its bits reversed, from the generator matrix (direction
// numbers v_1 = 2^31, v_k = v_{k−1} ⊕ v_{k−1}/2), one 256-entry table per index byte.
// Reversed, because the Owen scramble that follows works on reversed bits.
struct Sobol1Tables {
    uint32_t t[4][256];
    constexpr Sobol1Tables() : t{} {
        uint32_t v[32] = {};
        v[0] = 1u << 31;
        for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
        for (int b = 0; b < 4; ++b)
            for (uint32_t i = 0; i < 256; ++i) {
                uint32_t r = 0;
                for (int k = 0; k < 8; ++k)
                    if (i >> k & 1) r ^= reverse_bits(v[8 * b + k]);
                t[b][i] = r;
            }
    }
};
inline constexpr Sobol1Tables sobol1_tables{};

constexpr uint32_t reversed_sobol1(uint32_t i) {
    return sobol1_tables.t[0][i & 0xff] ^ sobol1_tables.t[1][(i >> 8) & 0xff] ^
           sobol1_tables.t[2][(i >> 16) & 0xff] ^ sobol1_tables.t[3][i >> 24];
}

constexpr float to_unit(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

}  // namespace sobol_detail

class Sampler {
  public:
    enum class Kind : uint8_t { sobol, independent };

    Sampler() = default;  // for arrays of per-pixel streams; assign before use
    Sampler(uint64_t seed, uint32_t frame, Kind kind = Kind::sobol)
        : m_base(mix64(seed ^ mix64(golden_gamma + frame))), m_kind(kind) {}

    // Starts the stream of one pixel sample; dimensions restart at 0.
    void start_pixel_sample(uint32_t x, uint32_t y, uint32_t sample) {
        m_pixel = mix64(m_base ^ mix64((uint64_t(x) << 32 | y) + 0x632be59bd9b4e019ull));
        m_sample = sample;
        m_reversed_sample = sobol_detail::reverse_bits(sample);
        m_dim = 0;
    }
    // A uniform float in [0, 1).
    float get_1d() {
        const uint64_t h = dimension_hash();
        if (m_kind == Kind::independent) return float(h >> 40) * 0x1p-24f;
        // Sobol's first dimension is the index reversed (van der Corput): the scrambled
        // point of the shuffled index i is owen(reverse(i)), i.e. LK(i) reversed.
        using namespace sobol_detail;
        const uint32_t i = owen_scramble_reversed(m_reversed_sample, uint32_t(h));
        return to_unit(owen_scramble_reversed(i, uint32_t(h >> 32)));
    }
    // Two uniform floats in [0, 1).
    struct Pair {
        float u1, u2;
    };
    Pair get_2d() {
        const uint64_t h = dimension_hash();
        if (m_kind == Kind::independent)
            // The top and the next 24 bits of a 64-bit splitmix output are independent
            // to the mix's full avalanche: one hash per pair.
            return {float(h >> 40) * 0x1p-24f, float((h >> 16) & 0xffffffu) * 0x1p-24f};
        using namespace sobol_detail;
        // The shuffled index, then Sobol's dimensions 0 and 1 of it, each scrambled; the
        // second coordinate's seed is the first's through an odd multiplier (the
        // permutation hashes it).
        const uint32_t i = owen_scramble_reversed(m_reversed_sample, uint32_t(h));
        const uint32_t s = uint32_t(h >> 32);
        return {to_unit(owen_scramble_reversed(i, s)),
                to_unit(owen_scramble_reversed(reversed_sobol1(i), s * 0x2c1b3c6du + 1))};
    }

  private:
    // The seed of the next dimension (pair) of this pixel: independent of the sample
    // index, so that every sample of the pixel scrambles the same way (a pixel's
    // samples are one scrambled net, not independent points).
    uint64_t dimension_hash() {
        const uint64_t d = uint64_t(++m_dim) * golden_gamma;
        return m_kind == Kind::independent
                   ? mix64(m_pixel + d + uint64_t(m_sample) * 0xd6e8feb86659fd93ull)
                   : mix64(m_pixel + d);
    }

    uint64_t m_base = 0;
    uint64_t m_pixel = 0;
    uint32_t m_sample = 0, m_reversed_sample = 0;
    uint32_t m_dim = 0;
    Kind m_kind = Kind::sobol;
};

}  // namespace pelage::renderer
