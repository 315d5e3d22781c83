// The few value types shared inside shader/hair. shader/ must not include renderer
// headers (data flows sim → shader → renderer), so the hair BSDF carries its own minimal
// vector and colour types; their layout ({x, y, z} floats) matches renderer/core/math.h
// so the renderer's wrapper converts member by member.
#pragma once

#include <cmath>

namespace pelage::hair {

inline constexpr float pi = 3.14159265358979323846f;

struct Vec3f {
    float x = 0, y = 0, z = 0;

    constexpr Vec3f operator+(Vec3f o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3f operator-(Vec3f o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3f operator*(Vec3f o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3f operator/(float s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3f &operator+=(Vec3f o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr bool operator==(const Vec3f &) const = default;
};

// Scene-linear Rec.709 RGB.
using Rgb = Vec3f;

constexpr Vec3f operator*(float s, Vec3f v) { return v * s; }
inline Rgb exp(Rgb c) { return {std::exp(c.x), std::exp(c.y), std::exp(c.z)}; }
constexpr float luminance(Rgb c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
constexpr float sqr(float x) { return x * x; }
inline float safe_sqrt(float x) { return std::sqrt(x > 0 ? x : 0.0f); }
inline float safe_asin(float x) { return std::asin(x < -1 ? -1.0f : (x > 1 ? 1.0f : x)); }

}  // namespace pelage::hair
