// The closest point of a mesh to a point in space, by testing every triangle: for the
// few landmark points of a "near" region (control_spec.h), snapped onto the surface.
#pragma once

#include "sim/mesh/mesh.h"

namespace pelage::sim {

// The closest point of triangle abc to p (C. Ericson, Real-Time Collision Detection,
// 2005, §5.1.5).
Vec3d closest_point_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c);

struct ClosestSurfacePoint {
    TriId tri = 0;
    Vec3d point;
    double distance = 0;
};

// The lowest-numbered triangle among the closest ones (deterministic).
ClosestSurfacePoint closest_surface_point(const TriangleMesh &mesh, Vec3d p);

}  // namespace pelage::sim
