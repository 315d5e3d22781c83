#include "sim/control/closest_point.h"

#include <limits>

namespace pelage::sim {

Vec3d closest_point_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;  // vertex region a
    const Vec3d bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;  // vertex region b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));  // edge ab
    const Vec3d cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;  // vertex region c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));  // edge ac
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)  // edge bc
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1 / (va + vb + vc);  // inside the face
    return a + ab * (vb * denom) + ac * (vc * denom);
}

ClosestSurfacePoint closest_surface_point(const TriangleMesh &mesh, Vec3d p) {
    ClosestSurfacePoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (TriId t = 0; t < mesh.num_triangles(); ++t) {
        const Vec3d q = closest_point_on_triangle(p, mesh.vertex(t, 0), mesh.vertex(t, 1),
                                                  mesh.vertex(t, 2));
        const double d = length(q - p);
        if (d < best.distance) best = {t, q, d};
    }
    return best;
}

}  // namespace pelage::sim
