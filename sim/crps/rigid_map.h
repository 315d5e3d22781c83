// A 2D rigid transform stored as (cos θ, sin θ, Ax, Ay): Teo 2006 §4.3, eq. for F_ji —
// p' = [C -S; S C] p + A, four multiplies and four adds per point.
#pragma once

#include <cmath>

#include "sim/core/vec.h"

namespace pelage::sim {

struct RigidMap2 {
    double c = 1, s = 0, ax = 0, ay = 0;

    constexpr Vec2d apply(Vec2d p) const {
        return {c * p.x - s * p.y + ax, s * p.x + c * p.y + ay};
    }
    constexpr Vec2d apply_direction(Vec2d d) const {
        return {c * d.x - s * d.y, s * d.x + c * d.y};
    }

    // Teo §4.3, F_ij = T(M_j) R(-θ) T(-M_i): the reverse map.
    constexpr RigidMap2 inverse() const {
        return {c, -s, -(c * ax + s * ay), s * ax - c * ay};
    }

    // The rigid map taking direction d_from to direction d_to (both non-zero) and the
    // point p_from to p_to.
    static RigidMap2 aligning(Vec2d d_from, Vec2d d_to, Vec2d p_from, Vec2d p_to) {
        double c = dot(d_from, d_to), s = cross(d_from, d_to);
        const double n = std::hypot(c, s);
        c /= n;
        s /= n;
        const Vec2d r{c * p_from.x - s * p_from.y, s * p_from.x + c * p_from.y};
        return {c, s, p_to.x - r.x, p_to.y - r.y};
    }
};

// (a ∘ b)(p) = a(b(p)): composing along a breadth-first path, Teo §4.1.
constexpr RigidMap2 compose(const RigidMap2 &a, const RigidMap2 &b) {
    return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s, a.c * b.ax - a.s * b.ay + a.ax,
            a.s * b.ax + a.c * b.ay + a.ay};
}

}  // namespace pelage::sim
