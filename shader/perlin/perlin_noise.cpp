// Implements Perlin 2002 (see perlin_noise.h).
#include "shader/perlin/perlin_noise.h"

#include <cmath>
#include <numeric>

namespace pelage::shader::perlin {
namespace {

float fade(float t) {
    return t * t * t * (t * (t * 6 - 15) + 10);
}  // Perlin 2002 eq. for s(t)
float lerp(float t, float a, float b) { return a + t * (b - a); }

// The 12 gradients (±1, ±1, 0) and permutations, picked by the low 4 bits of the hash
// (16 entries: four repeated, as in Perlin 2002 §3).
float grad(uint8_t hash, float x, float y, float z) {
    const int h = hash & 15;
    const float u = h < 8 ? x : y;
    const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

}  // namespace

PerlinNoise::PerlinNoise(uint32_t seed) {
    std::array<uint8_t, 256> p;
    std::iota(p.begin(), p.end(), 0);
    // Fisher-Yates with a xorshift32 stream: deterministic per seed on every platform.
    uint32_t s = seed * 0x9E3779B9u + 0x7F4A7C15u;
    if (s == 0) s = 1;
    for (int i = 255; i > 0; --i) {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        std::swap(p[i], p[s % (i + 1)]);
    }
    for (int i = 0; i < 512; ++i) m_perm[i] = p[i & 255];
}

float PerlinNoise::noise(float x, float y, float z) const {
    const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const int X = static_cast<int>(static_cast<int64_t>(fx) & 255);
    const int Y = static_cast<int>(static_cast<int64_t>(fy) & 255);
    const int Z = static_cast<int>(static_cast<int64_t>(fz) & 255);
    x -= fx;
    y -= fy;
    z -= fz;
    const float u = fade(x), v = fade(y), w = fade(z);
    const auto &P = m_perm;
    const int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z;
    const int B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
    return lerp(
        w,
        lerp(v, lerp(u, grad(P[AA], x, y, z), grad(P[BA], x - 1, y, z)),
             lerp(u, grad(P[AB], x, y - 1, z), grad(P[BB], x - 1, y - 1, z))),
        lerp(v, lerp(u, grad(P[AA + 1], x, y, z - 1), grad(P[BA + 1], x - 1, y, z - 1)),
             lerp(u, grad(P[AB + 1], x, y - 1, z - 1),
                  grad(P[BB + 1], x - 1, y - 1, z - 1))));
}

float PerlinNoise::fbm(float x, float y, float z, int octaves, float lacunarity,
                       float gain) const {
    float sum = 0, amplitude = 1, norm = 0, f = 1;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * noise(x * f, y * f, z * f);
        norm += amplitude;
        amplitude *= gain;
        f *= lacunarity;
    }
    return norm > 0 ? sum / norm : 0.0f;
}

}  // namespace pelage::shader::perlin
