#include "sim/mesh/mesh.h"

#include <algorithm>

namespace pelage::sim {

void Bounds3::extend(Vec3d p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
}

double Bounds3::diagonal() const { return hi.x < lo.x ? 0.0 : length(hi - lo); }

Vec3d TriangleMesh::face_normal_unnormalized(TriId t) const {
    const Vec3d p0 = vertex(t, 0);
    return cross(vertex(t, 1) - p0, vertex(t, 2) - p0);
}

double TriangleMesh::triangle_area(TriId t) const {
    return 0.5 * length(face_normal_unnormalized(t));
}

Bounds3 TriangleMesh::bounds() const {
    Bounds3 b;
    for (const Vec3d &p : positions) b.extend(p);
    return b;
}

double TriangleMesh::surface_area() const {
    double a = 0;
    for (TriId t = 0; t < num_triangles(); ++t) a += triangle_area(t);
    return a;
}

}  // namespace pelage::sim
