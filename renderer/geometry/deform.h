// Deforming meshes: a pose is a second mesh with the same topology as the rest mesh
// (same vertex count, same triangles in the same order); only positions change. The
// pattern of a shader that looks up (triangle, barycentrics) — the clonal mosaic — rides
// on the surface; one that evaluates object-space position (worley, perlin) swims.
#pragma once

#include <string>

#include "sim/mesh/mesh.h"

namespace pelage::renderer {

// Rest positions blended towards the pose in `pose_path` by `weight` (0 rest, 1 pose).
// Throws pelage::InputError naming the pose file and `field` (e.g. "objects[0].deform")
// when the topology differs. Shading normals from the rest file are dropped (they do not
// follow the deformation).
void apply_pose(sim::TriangleMesh &rest, const std::string &pose_path, float weight,
                const std::string &scene_path, const std::string &field);

}  // namespace pelage::renderer
