// The vector types every layer builds on (sim -> shader -> renderer, so they live in the
// lowest layer).
//   * pelage::Vec3f (and Rgb): single precision, for the hot paths of the shaders and the
//     renderer; colours are scene-linear Rec.709 RGB. In namespace pelage, so code in any
//     pelage:: namespace names it unqualified.
//   * pelage::sim::Vec2d, Vec3d, Mat3d: double precision, for the simulation's geometry.
//     The CRPS is built once, and its 2D <-> 3D round trip must stay exact to ~1e-6 of
//     the mesh size.
#pragma once

#include <algorithm>
#include <cmath>

namespace pelage {

inline constexpr float pi = 3.14159265358979323846f;
inline constexpr float inv_pi = 0.31830988618379067154f;

struct Vec3f {
    float x = 0, y = 0, z = 0;

    constexpr Vec3f operator+(Vec3f o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3f operator-(Vec3f o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3f operator-() const { return {-x, -y, -z}; }
    constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3f operator*(Vec3f o) const { return {x * o.x, y * o.y, z * o.z}; }
    // One division and three multiplies; the result may differ from a true quotient by
    // an ulp. divide_exactly() below divides each component.
    constexpr Vec3f operator/(float s) const {
        const float inv = 1.0f / s;
        return {x * inv, y * inv, z * inv};
    }
    constexpr Vec3f &operator+=(Vec3f o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3f &operator*=(Vec3f o) {
        x *= o.x;
        y *= o.y;
        z *= o.z;
        return *this;
    }
    constexpr Vec3f &operator*=(float s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr bool operator==(const Vec3f &) const = default;
};

// Scene-linear Rec.709 RGB.
using Rgb = Vec3f;

constexpr Vec3f operator*(float s, Vec3f v) { return v * s; }
// Three divisions: each component is the correctly rounded quotient. The hair BSDF and
// the fur strands divide this way; operator/ rounds the reciprocal first, so trading one
// for the other moves results by an ulp.
constexpr Vec3f divide_exactly(Vec3f v, float s) { return {v.x / s, v.y / s, v.z / s}; }
constexpr float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(Vec3f a, Vec3f b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f a) { return std::sqrt(dot(a, a)); }
inline Vec3f normalize(Vec3f a) { return a / length(a); }
constexpr float max_component(Vec3f a) { return std::max(a.x, std::max(a.y, a.z)); }
inline bool is_finite(Vec3f a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline Rgb exp(Rgb c) { return {std::exp(c.x), std::exp(c.y), std::exp(c.z)}; }
constexpr bool is_black(Rgb c) { return c.x == 0 && c.y == 0 && c.z == 0; }
// Rec.709 luma weights.
constexpr float luminance(Rgb c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

constexpr float sqr(float x) { return x * x; }
// sqrt and asin with the argument clamped to their domain, for arguments that leave it
// only by rounding.
inline float safe_sqrt(float x) { return std::sqrt(x > 0 ? x : 0.0f); }
inline float safe_asin(float x) { return std::asin(x < -1 ? -1.0f : (x > 1 ? 1.0f : x)); }

}  // namespace pelage

namespace pelage::sim {

struct Vec2d {
    double x = 0, y = 0;

    constexpr Vec2d operator+(Vec2d o) const { return {x + o.x, y + o.y}; }
    constexpr Vec2d operator-(Vec2d o) const { return {x - o.x, y - o.y}; }
    constexpr Vec2d operator*(double s) const { return {x * s, y * s}; }
    constexpr Vec2d operator/(double s) const { return {x / s, y / s}; }
    constexpr Vec2d &operator+=(Vec2d o) {
        x += o.x;
        y += o.y;
        return *this;
    }
    constexpr bool operator==(const Vec2d &) const = default;
};

constexpr double dot(Vec2d a, Vec2d b) { return a.x * b.x + a.y * b.y; }
// z component of the 3D cross product: > 0 when b is counter-clockwise from a.
constexpr double cross(Vec2d a, Vec2d b) { return a.x * b.y - a.y * b.x; }
inline double length(Vec2d a) { return std::sqrt(dot(a, a)); }
constexpr double length_squared(Vec2d a) { return dot(a, a); }

struct Vec3d {
    double x = 0, y = 0, z = 0;

    constexpr Vec3d operator+(Vec3d o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3d operator-(Vec3d o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3d operator-() const { return {-x, -y, -z}; }
    constexpr Vec3d operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3d operator/(double s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3d &operator+=(Vec3d o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr bool operator==(const Vec3d &) const = default;
};

constexpr double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3d a) { return std::sqrt(dot(a, a)); }
constexpr double length_squared(Vec3d a) { return dot(a, a); }
inline Vec3d normalize(Vec3d a) { return a / length(a); }
inline bool is_finite(Vec3d a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// Row-major 3x3 matrix; only rotations are stored in it.
struct Mat3d {
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    constexpr Vec3d operator*(Vec3d v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    // R^T v: the inverse of a rotation.
    constexpr Vec3d transpose_times(Vec3d v) const {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z,
                m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
};

}  // namespace pelage::sim
