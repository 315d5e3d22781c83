// The scene as one frame of its animation shows it: the camera orbited or the objects
// turned by a turntable, each clip's pose time (and its times in the shutter), a
// deformation's pose and weight, a growing body's age. The scene file's reader
// (renderer/scene_file) says what the animation is; this evaluates it at a frame.
#pragma once

#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

// Rotation by `degrees` about `axis` (unit) through `center`.
Affine rotation_about(Vec3f axis, Vec3f center, float degrees);
// The turntable angle at frame `frame` plus `time` (in frames, the shutter position).
float turntable_degrees(const AnimationDesc &a, double frame_time);
// The camera at frame + time (time in frames): orbited for a camera turntable.
CameraDesc camera_at(const SceneDesc &scene, double frame_time);
// The scene as frame `frame` shows it (shutter open): camera orbited or objects turned,
// deforming objects at their pose for the frame.
SceneDesc scene_at_frame(const SceneDesc &scene, int frame);

}  // namespace pelage::renderer
