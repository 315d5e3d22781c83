// The body length (sim/crps/body_length.h) against shapes whose principal axis and
// extent are known: an elongated box turned to an arbitrary orientation, and a sphere.
#include "sim/crps/body_length.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/crps/surface.h"
#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

// A closed box a × b × c, each face split into n × n quads, rotated by `r`.
TriangleMesh box(double a, double b, double c, int n, const Mat3d &r) {
    TriangleMesh m;
    const Vec3d half{a / 2, b / 2, c / 2};
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {-1, 1}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const VertId first = VertId(m.positions.size());
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= n; ++i) {
                    double p[3];
                    p[axis] = side * half[axis];
                    p[u] = (2.0 * i / n - 1) * half[u];
                    p[v] = (2.0 * j / n - 1) * half[v];
                    m.positions.push_back(r * Vec3d{p[0], p[1], p[2]});
                }
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const VertId q = first + VertId(j * (n + 1) + i);
                    const VertId q1 = q + 1, q2 = q + VertId(n + 1), q3 = q2 + 1;
                    if (side > 0) {
                        m.triangles.push_back({q, q1, q3});
                        m.triangles.push_back({q, q3, q2});
                    } else {
                        m.triangles.push_back({q, q3, q1});
                        m.triangles.push_back({q, q2, q3});
                    }
                }
        }
    return m;
}

Mat3d rotation(Vec3d axis, double angle) {  // Rodrigues
    const Vec3d k = normalize(axis);
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    Mat3d m;
    m.m[0][0] = c + k.x * k.x * t, m.m[0][1] = k.x * k.y * t - k.z * s;
    m.m[0][2] = k.x * k.z * t + k.y * s, m.m[1][0] = k.y * k.x * t + k.z * s;
    m.m[1][1] = c + k.y * k.y * t, m.m[1][2] = k.y * k.z * t - k.x * s;
    m.m[2][0] = k.z * k.x * t - k.y * s, m.m[2][1] = k.z * k.y * t + k.x * s;
    m.m[2][2] = c + k.z * k.z * t;
    return m;
}

TEST(BodyLength, AnElongatedBoxInAnyOrientationAndTessellation) {
    const Mat3d r = rotation({0.3, -0.7, 0.5}, 1.1);
    for (int n : {1, 6}) {
        const Surface s = build_surface(box(4, 1, 0.5, n, r));
        const BodyAxis b = body_axis(s.crps);
        EXPECT_NEAR(b.length, 4.0, 1e-9) << n;
        const Vec3d along = r * Vec3d{1, 0, 0};
        EXPECT_NEAR(std::abs(dot(b.axis, along)), 1.0, 1e-9) << n;
        EXPECT_NEAR(length(b.centroid), 0.0, 1e-9) << n;
    }
}

TEST(BodyLength, ASphereIsItsDiameterLong) {
    const Surface s = build_surface(make_icosphere(3, 2.5));
    EXPECT_NEAR(body_axis(s.crps).length, 5.0, 0.05);
}

}  // namespace
}  // namespace pelage::sim
