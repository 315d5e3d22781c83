// Sine and cosine for the samplers' angles, as inlined polynomials instead of libm's
// sincosf (a call per sample, a visible share of a render). Only + and × on floats:
// without -march the compiler has no FMA to contract them into, so the results are the
// same bits on every x86-64 machine and at any thread count. On |x| ≤ π/4 the truncated
// Taylor series (Abramowitz & Stegun 4.3.65/4.3.66) to x⁹ (sin) and x¹⁰ (cos) leave a
// remainder below 2e-9, under float rounding: |error| ≤ 1.0e-7 against double precision
// over 2²² angles 2πu (libm on the rounded float angle: 4.1e-7), as SinCos.* in
// tests/renderer/core/sampling_test.cpp checks.
#pragma once

#include "renderer/core/math.h"

namespace pelage::renderer {

// sin x and cos x for |x| ≤ π/4.
inline void sin_cos_quarter(float x, float *s, float *c) {
    const float x2 = x * x;
    *s = x * (1 + x2 * (-1.0f / 6 +
                        x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    *c = 1 + x2 * (-0.5f +
                   x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 +
                                                               x2 * (-1.0f / 3628800)))));
}

// sin and cos of the angle 2πu, u in [0, 1]: the nearest quarter turn k is taken out
// exactly (4u − k needs no rounding), the rest is within ±π/4.
inline void sin_cos_turn(float u, float *s, float *c) {
    const float t = 4 * u;
    const int k = int(t + 0.5f);
    float sr, cr;
    sin_cos_quarter((t - float(k)) * (pi / 2), &sr, &cr);
    switch (k & 3) {
        case 0:
            *s = sr, *c = cr;
            break;
        case 1:
            *s = cr, *c = -sr;
            break;
        case 2:
            *s = -sr, *c = -cr;
            break;
        default:
            *s = -cr, *c = sr;
            break;
    }
}

}  // namespace pelage::renderer
