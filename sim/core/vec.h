// Small fixed-size vector types for the geometric core. Double precision: the CRPS is
// built once, and its 2D <-> 3D round trip must stay exact to ~1e-6 of the mesh size.
#pragma once

#include <cmath>

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
