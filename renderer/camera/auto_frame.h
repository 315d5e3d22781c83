// Automatic framing of one object: a three-quarter view that fits the object's points in
// the picture, and the ground under it. `pelage look` places a camera this way on any
// mesh, whatever its units and extent.
#pragma once

#include <vector>

#include "renderer/core/math.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct FramingRequest {
    Vec3f up{0, 1, 0};   // the object's up direction (unit)
    float fov_deg = 30;  // vertical field of view
    float aspect = 16.0f / 9.0f;
    // Every point lands inside the image shrunk by this fraction of its half-size on each
    // side, and one touches that border.
    float margin = 0.08f;
    // The view from the side of the body (perpendicular to its long horizontal axis)
    // turned by `azimuth` towards its +long end, raised by `elevation`.
    float azimuth_deg = 35, elevation_deg = 15;
    // Non-zero: the body's long axis to view from, its sign kept: +long is the end the
    // view turns towards, an animal's head (renderer/camera/body_facing.h). Zero: the
    // points' own axis, of either sign.
    Vec3f long_axis{0, 0, 0};
    // Non-zero: the side of the body the camera stands on (its component across the
    // long axis picks one of the two); zero: cross(up, long).
    Vec3f side_axis{0, 0, 0};
};

struct Framing {
    CameraDesc camera;
    Vec3f center;                // of the bounding box
    float radius = 0;            // of the bounding sphere about `center`
    Vec3f long_axis, side_axis;  // horizontal: along the body, and across it
    float ground = 0;            // the lowest point's height along `up`
    Vec3f view;                  // unit, from `center` towards the camera
};

// The dominant direction of the points projected on the plane ⟂ `up` (unit), about the
// centre of their bounding box (2-D principal component; its sign is arbitrary), or any
// horizontal direction when they have none. `up` is unit; the points are not empty.
Vec3f long_horizontal_axis(const std::vector<Vec3f> &points, Vec3f up);

// Throws std::invalid_argument for no points, non-finite points or a zero `up`.
Framing frame_points(const std::vector<Vec3f> &points, const FramingRequest &request);

}  // namespace pelage::renderer
