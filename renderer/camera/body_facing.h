// Which way an animal faces, so that `pelage look`'s camera (auto_frame.h) turns towards
// its head rather than its rump: the sign of the body's long horizontal axis, from the
// file format's convention where it has one, else from the body's shape.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/math.h"

namespace pelage::renderer {

struct BodyFacing {
    Vec3f long_axis;  // unit, horizontal: from the body's middle towards its head
    Vec3f side_axis;  // unit, horizontal, ⟂ long_axis: the side the camera stands on
    enum class Rule { front, shape } rule = Rule::shape;  // what signed `long_axis`
};

// The files whose format says which way an asset faces: glTF 2.0 (.gltf, .glb), §3.4
// "Coordinate System and Units": "the front of a glTF asset faces +Z". Zero for every
// other file (and procedural meshes): their shape decides.
Vec3f format_front(const std::string &mesh_path);

// The head end of a body, by shape: the outer 30 % of its length at each end, and
// in it the surface above the body's mean height (area-weighted over the whole
// surface), weighted by how far above: Σ area·(h − h̄) over those triangles. A head
// and neck are raised and massive, a tail is thin and a rump is no higher than the
// back, so the end with the larger sum is the head. Returns `long_axis` or its
// opposite (`long_axis` itself on a tie).
Vec3f towards_head(const std::vector<Vec3f> &positions,
                   const std::vector<std::array<uint32_t, 3>> &triangles, Vec3f up,
                   Vec3f long_axis);

// The body's long horizontal axis (auto_frame.h's, over the triangles' corners), signed
// towards the head, and the side to view it from. A non-zero `front` (format_front)
// decides when the long axis lies within 45° of its horizontal part: +long is the end
// it points to. When the body lies across it, the camera stands on the side `front`
// points to and the shape picks the head end. A `front` along `up` (a glTF stood up on
// another axis) says nothing. Throws std::invalid_argument when no triangle has
// finite corners or `up` is zero.
BodyFacing body_facing(const std::vector<Vec3f> &positions,
                       const std::vector<std::array<uint32_t, 3>> &triangles, Vec3f up,
                       Vec3f front);

}  // namespace pelage::renderer
