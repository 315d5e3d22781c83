#include "sim/crps/body_length.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pelage::sim {

BodyAxis body_axis(const Crps &crps) {
    BodyAxis b;
    const size_t nt = crps.num_triangles();
    double area = 0;
    for (TriId t = 0; t < nt; ++t) {
        const CrpsFrame &f = crps.frame(t);
        b.centroid = b.centroid + crps.to_3d(t, {0, 0}) * f.area;  // (0, 0) = centroid
        area += f.area;
    }
    if (area <= 0) return b;
    b.centroid = b.centroid * (1 / area);

    // Second moment of each triangle about the body's centroid, exact for a triangle:
    // ∫ x xᵀ dA = A/12 (Σ p_k p_kᵀ + s sᵀ), s = Σ p_k (p relative to the centroid).
    double c[3][3] = {};
    for (TriId t = 0; t < nt; ++t) {
        const CrpsFrame &f = crps.frame(t);
        Vec3d p[3], s;
        for (int k = 0; k < 3; ++k) s = s + (p[k] = crps.to_3d(t, f.v[k]) - b.centroid);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double m = s[i] * s[j];
                for (int k = 0; k < 3; ++k) m += p[k][i] * p[k][j];
                c[i][j] += f.area / 12 * m;
            }
    }
    // Power iteration from the column of largest norm (never orthogonal to the dominant
    // eigenvector unless the moment is isotropic, where every axis is principal).
    auto apply = [&](Vec3d v) {
        return Vec3d{c[0][0] * v.x + c[0][1] * v.y + c[0][2] * v.z,
                     c[1][0] * v.x + c[1][1] * v.y + c[1][2] * v.z,
                     c[2][0] * v.x + c[2][1] * v.y + c[2][2] * v.z};
    };
    Vec3d v{1, 0, 0};
    double best = -1;
    for (const Vec3d &e : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}})
        if (const double n = length(apply(e)); n > best) best = n, v = apply(e);
    for (int it = 0; it < 200 && length(v) > 0; ++it) v = normalize(apply(v));
    if (!(length(v) > 0)) v = {1, 0, 0};
    b.axis = normalize(v);

    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (TriId t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const double x = dot(crps.to_3d(t, crps.frame(t).v[k]) - b.centroid, b.axis);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
    b.length = hi - lo;
    return b;
}

}  // namespace pelage::sim
