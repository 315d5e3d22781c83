// Implements Worley 1996 (see worley_noise.h).
#include "shader/worley/worley_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pelage::shader::worley {
namespace {

uint32_t hash3(int32_t x, int32_t y, int32_t z, uint32_t seed) {
    // A 32-bit integer mix of the cube's coordinates (multiply-xorshift).
    uint32_t h = seed * 0x9E3779B9u;
    h ^= static_cast<uint32_t>(x) * 0x85EBCA6Bu;
    h = (h ^ (h >> 15)) * 0x2C1B3C6Du;
    h ^= static_cast<uint32_t>(y) * 0xC2B2AE35u;
    h = (h ^ (h >> 13)) * 0x297A2D39u;
    h ^= static_cast<uint32_t>(z) * 0x27D4EB2Fu;
    h = (h ^ (h >> 16)) * 0x85EBCA6Bu;
    return h ^ (h >> 13);
}

uint32_t next(uint32_t &state) {  // xorshift32 stream seeded by the cube's hash
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state;
}

// Poisson(mean) deviate from one uniform number by inverting the CDF (Worley §3 uses a
// precomputed table for the same purpose). Capped at 16 points per cube.
int poisson_count(float u, float mean) {
    float p = std::exp(-mean), cdf = p;
    int k = 0;
    while (u > cdf && k < 16) {
        ++k;
        p *= mean / k;
        cdf += p;
    }
    return k;
}

}  // namespace

int worley_cube_points(int32_t x, int32_t y, int32_t z, uint32_t seed, float mean_points,
                       float points[16][3], uint32_t ids[16]) {
    uint32_t state = hash3(x, y, z, seed) | 1u;
    const int n = poisson_count((next(state) >> 8) * 0x1p-24f, mean_points);
    for (int i = 0; i < n; ++i) {
        ids[i] = next(state);
        points[i][0] = x + (next(state) >> 8) * 0x1p-24f;
        points[i][1] = y + (next(state) >> 8) * 0x1p-24f;
        points[i][2] = z + (next(state) >> 8) * 0x1p-24f;
    }
    return n;
}

WorleyResult worley(const float p[3], uint32_t seed, float mean_points) {
    const int32_t cx = static_cast<int32_t>(std::floor(p[0]));
    const int32_t cy = static_cast<int32_t>(std::floor(p[1]));
    const int32_t cz = static_cast<int32_t>(std::floor(p[2]));
    float d1 = std::numeric_limits<float>::infinity(), d2 = d1;
    uint32_t id1 = 0;
    // Search rings of cubes outward; a ring at Chebyshev distance k cannot hold a point
    // nearer than (k - 1), so stop once F2 is below that.
    for (int32_t k = 0; k < 8; ++k) {
        if (k >= 2 && d2 <= float(k - 1) * float(k - 1)) break;  // d2 is squared
        for (int32_t dx = -k; dx <= k; ++dx)
            for (int32_t dy = -k; dy <= k; ++dy)
                for (int32_t dz = -k; dz <= k; ++dz) {
                    if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != k)
                        continue;
                    float pts[16][3];
                    uint32_t ids[16];
                    const int n = worley_cube_points(cx + dx, cy + dy, cz + dz, seed,
                                                     mean_points, pts, ids);
                    for (int i = 0; i < n; ++i) {
                        const float d = (pts[i][0] - p[0]) * (pts[i][0] - p[0]) +
                                        (pts[i][1] - p[1]) * (pts[i][1] - p[1]) +
                                        (pts[i][2] - p[2]) * (pts[i][2] - p[2]);
                        if (d < d1) {
                            d2 = d1;
                            d1 = d;
                            id1 = ids[i];
                        } else if (d < d2) {
                            d2 = d;
                        }
                    }
                }
    }
    return {std::sqrt(d1), std::sqrt(d2), id1};
}

}  // namespace pelage::shader::worley
