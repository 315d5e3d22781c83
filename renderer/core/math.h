// The renderer's geometric helpers on the core vector type (sim/core/vec.h): frames,
// affine transforms and ray-origin offsets.
#pragma once

#include <algorithm>
#include <cmath>

#include "sim/core/vec.h"

namespace pelage::renderer {

// An orthonormal basis around n (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited", JCGT 6(1)); local z is n.
struct Frame {
    Vec3f s, t, n;
    static Frame from_z(Vec3f n) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
        return {{1 + sign * n.x * n.x * a, sign * b, -sign * n.x},
                {b, sign + n.y * n.y * a, -n.y},
                n};
    }
    Vec3f to_local(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3f to_world(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

// Row-major affine 3x4 transform.
struct Affine {
    float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    Vec3f point(Vec3f p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3f vector(Vec3f v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    Affine operator*(const Affine &b) const {
        Affine r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) {
                float s = j == 3 ? m[i][3] : 0.0f;
                for (int k = 0; k < 3; ++k) s += m[i][k] * b.m[k][j];
                r.m[i][j] = s;
            }
        return r;
    }
    bool is_identity() const {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j)
                if (m[i][j] != (i == j ? 1.0f : 0.0f)) return false;
        return true;
    }
    float determinant3() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // The inverse transpose of the linear part, for normals (unnormalized).
    Affine normal_matrix() const {
        Affine r;
        const float d = determinant3();
        const float inv = d != 0 ? 1.0f / d : 0.0f;
        // Cofactor matrix / det = inverse transpose.
        r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
        r.m[0][1] = -(m[1][0] * m[2][2] - m[1][2] * m[2][0]) * inv;
        r.m[0][2] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
        r.m[1][0] = -(m[0][1] * m[2][2] - m[0][2] * m[2][1]) * inv;
        r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
        r.m[1][2] = -(m[0][0] * m[2][1] - m[0][1] * m[2][0]) * inv;
        r.m[2][0] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
        r.m[2][1] = -(m[0][0] * m[1][2] - m[0][2] * m[1][0]) * inv;
        r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
        r.m[0][3] = r.m[1][3] = r.m[2][3] = 0;
        return r;
    }
};

// Moves a ray origin off a surface along the geometric normal, to the side `w` leaves
// towards, so the new ray does not hit the surface it starts on. The offset scales with
// the magnitude of the coordinates, as float rounding error does.
inline Vec3f offset_ray_origin(Vec3f p, Vec3f ng, Vec3f w) {
    constexpr float relative = 1e-5f, absolute = 1e-5f;
    const float mag = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    const float eps = absolute + relative * mag;
    return p + ng * (dot(w, ng) >= 0 ? eps : -eps);
}

}  // namespace pelage::renderer
