#include "renderer/fur/strand_shape.h"

#include <algorithm>
#include <cmath>

namespace pelage::renderer {

namespace {

// a / |a| with |a|² clamped away from 0, so a degenerate direction stays finite.
Vec3f unit(Vec3f a) { return divide_exactly(a, std::sqrt(std::max(dot(a, a), 1e-30f))); }

// Any unit vector ⊥ n (Duff et al. 2017, JCGT 6(1), first basis vector).
Vec3f any_perpendicular(Vec3f n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    return {1 + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x};
}

constexpr float deg = 3.14159265358979323846f / 180;
// Keep the strand out of the skin: its direction never dips below this sine of the
// angle to the root's tangent plane.
constexpr float min_lift = 0.05f;

}  // namespace

Vec3f comb_tangent(const FurParams &params, Vec3f n, Vec3f c) {
    if (params.comb == FurParams::Comb::normal) return any_perpendicular(n);
    const Vec3f t = c - n * dot(c, n);
    return dot(c, c) > 0 && dot(t, t) > 1e-8f * dot(c, c) ? unit(t)
                                                          : any_perpendicular(n);
}

void grow_centre_line(const FurParams &params, const StrandGroom &groom, Vec3f p, Vec3f n,
                      Vec3f comb, float L, const StrandRandom &r, Vec3f *out) {
    const int S = params.segments;
    // --- Root direction: tilted up from the comb tangent, then jittered ---
    const float angle =
        params.comb == FurParams::Comb::normal ? 90 * deg : groom.comb_angle_deg * deg;
    const Vec3f t = comb_tangent(params, n, comb), b = cross(n, t);
    Vec3f d = unit(t * std::cos(angle) + n * std::sin(angle));
    {
        const float az = 2 * pi * r.jitter_u;
        const float tilt = std::tan(params.comb_jitter_deg * deg) * std::sqrt(r.jitter_v);
        d = unit(d + (t * std::cos(az) + b * std::sin(az)) * tilt);
        if (dot(d, n) < min_lift) d = unit(d + n * (min_lift - dot(d, n)));
    }
    // --- Helix axes ⊥ the root direction, rotated by the strand's phase ---
    const Vec3f h0 =
        unit(cross(d, std::abs(d.y) < 0.9f ? Vec3f{0, 1, 0} : Vec3f{1, 0, 0}));
    const Vec3f h1 = cross(d, h0);
    const float phase = 2 * pi * r.curl_phase;
    const Vec3f ca = h0 * std::cos(phase) + h1 * std::sin(phase),
                cb = h1 * std::cos(phase) - h0 * std::sin(phase);
    const float curl_r = groom.curl_radius * L;
    // --- March: each segment bends towards −y by gravity/S, staying off the skin ---
    const float step = L / float(S);
    Vec3f q = p;
    out[0] = p;
    for (int k = 1; k <= S; ++k) {
        q += d * step;
        const float s = float(k) / float(S);
        const float theta = 2 * pi * groom.curl_turns * s;
        // The helix starts at the root (offset 0 at s = 0).
        out[k] =
            q + ca * (curl_r * (std::cos(theta) - 1)) + cb * (curl_r * std::sin(theta));
        d = unit(d + Vec3f{0, -1, 0} * (params.gravity / float(S)));
        if (dot(d, n) < min_lift) d = unit(d + n * (min_lift - dot(d, n)));
    }
}

}  // namespace pelage::renderer
