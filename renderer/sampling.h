// Warps from the unit square to directions and discs, with their densities.
#pragma once

#include <cmath>

#include "renderer/math.h"

namespace pelage::renderer {

// Concentric map (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square").
inline void sample_disk(float u1, float u2, float *dx, float *dy) {
    const float a = 2 * u1 - 1, b = 2 * u2 - 1;
    if (a == 0 && b == 0) {
        *dx = *dy = 0;
        return;
    }
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (pi / 4) * (b / a);
    } else {
        r = b;
        phi = pi / 2 - (pi / 4) * (a / b);
    }
    *dx = r * std::cos(phi);
    *dy = r * std::sin(phi);
}

// Cosine-weighted hemisphere about +z; density cos θ / π.
inline Vec3f sample_cosine_hemisphere(float u1, float u2) {
    float x, y;
    sample_disk(u1, u2, &x, &y);
    return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
}

// Uniform sphere; density 1 / (4π).
inline Vec3f sample_uniform_sphere(float u1, float u2) {
    const float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z)),
                phi = 2 * pi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform cone about +z with cos θ >= cos_max; density 1 / (2π (1 − cos_max)).
inline Vec3f sample_uniform_cone(float u1, float u2, float cos_max) {
    const float cos_t = 1 - u1 * (1 - cos_max),
                sin_t = std::sqrt(std::max(0.0f, 1 - cos_t * cos_t));
    const float phi = 2 * pi * u2;
    return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

// Veach's power heuristic (β = 2) for one sample from each of two strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace pelage::renderer
