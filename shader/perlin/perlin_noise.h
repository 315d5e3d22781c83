// Improved noise (K. Perlin, "Improving Noise", SIGGRAPH 2002): gradient noise on the
// integer lattice with the quintic fade 6t^5 - 15t^4 + 10t^3 and the twelve cube-edge
// gradients, plus its fractal sum (fBm). The permutation is a seeded shuffle of 0..255
// rather than the paper's fixed table, so every seed is a different pattern.
#pragma once

#include <array>
#include <cstdint>

namespace pelage::shader::perlin {

class PerlinNoise {
  public:
    explicit PerlinNoise(uint32_t seed);
    // Noise in about [-1, 1]; exactly 0 at lattice points.
    float noise(float x, float y, float z) const;
    // Sum of `octaves` octaves, frequency × lacunarity and amplitude × gain per octave,
    // normalised by the sum of amplitudes.
    float fbm(float x, float y, float z, int octaves, float lacunarity, float gain) const;

  private:
    std::array<uint8_t, 512> m_perm;  // doubled, so perm[perm[x] + y] never wraps
};

}  // namespace pelage::shader::perlin
