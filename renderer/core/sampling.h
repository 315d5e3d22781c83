// Warps from the unit square to directions and discs, with their densities.
#pragma once

#include <cmath>

#include "renderer/core/math.h"
#include "renderer/core/sin_cos.h"

namespace pelage::renderer {

// Concentric map (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square").
inline void sample_disk(float u1, float u2, float *dx, float *dy) {
    const float a = 2 * u1 - 1, b = 2 * u2 - 1;
    if (a == 0 && b == 0) {
        *dx = *dy = 0;
        return;
    }
    // φ = (π/4)(b/a) in the wedges |a| > |b|, else π/2 − (π/4)(a/b): cos and sin of
    // the second are the sin and cos of (π/4)(a/b), so both need only |x| ≤ π/4.
    float s, c;
    if (std::abs(a) > std::abs(b)) {
        sin_cos_quarter((pi / 4) * (b / a), &s, &c);
        *dx = a * c;
        *dy = a * s;
    } else {
        sin_cos_quarter((pi / 4) * (a / b), &s, &c);
        *dx = b * s;
        *dy = b * c;
    }
}

// Cosine-weighted hemisphere about +z; density cos θ / π. Malley's method through the
// polar map of the disc, r = √u1, φ = 2π u2 (PBR 3rd ed. §13.6.2–13.6.3): with pelage's
// unstratified hashed samples the concentric map's lower distortion buys nothing, and
// the polar map needs no division; z = √(1 − r²) = √(1 − u1) directly.
inline Vec3f sample_cosine_hemisphere(float u1, float u2) {
    float s, c;
    sin_cos_turn(u2, &s, &c);
    const float r = std::sqrt(u1);
    return {r * c, r * s, std::sqrt(std::max(0.0f, 1 - u1))};
}

// Uniform sphere; density 1 / (4π).
inline Vec3f sample_uniform_sphere(float u1, float u2) {
    const float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z));
    float s, c;
    sin_cos_turn(u2, &s, &c);  // φ = 2π u2
    return {r * c, r * s, z};
}

// Uniform cone about +z with cos θ >= cos_max; density 1 / (2π (1 − cos_max)).
inline Vec3f sample_uniform_cone(float u1, float u2, float cos_max) {
    const float cos_t = 1 - u1 * (1 - cos_max),
                sin_t = std::sqrt(std::max(0.0f, 1 - cos_t * cos_t));
    float s, c;
    sin_cos_turn(u2, &s, &c);  // φ = 2π u2
    return {sin_t * c, sin_t * s, cos_t};
}

// Veach's power heuristic (β = 2) for one sample from each of two strategies.
inline float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace pelage::renderer
