#include "sim/mesh/closest_point.h"

#include <limits>

namespace pelage::sim {

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
