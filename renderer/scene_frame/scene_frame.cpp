#include "renderer/scene_frame/scene_frame.h"

#include <algorithm>
#include <cmath>

#include "renderer/animation/rig.h"

namespace pelage::renderer {

Affine rotation_about(Vec3f axis, Vec3f center, float degrees) {
    // Rodrigues' rotation matrix, conjugated by the translation to `center`
    const double th = double(degrees) * 3.14159265358979323846 / 180;
    const double c = std::cos(th), sn = std::sin(th), t = 1 - c;
    const double x = axis.x, y = axis.y, z = axis.z;
    const double rot[3][3] = {{t * x * x + c, t * x * y - sn * z, t * x * z + sn * y},
                              {t * x * y + sn * z, t * y * y + c, t * y * z - sn * x},
                              {t * x * z - sn * y, t * y * z + sn * x, t * z * z + c}};
    Affine m;
    for (int i = 0; i < 3; ++i) {
        double off = center[i];
        for (int j = 0; j < 3; ++j) {
            m.m[i][j] = float(rot[i][j]);
            off -= rot[i][j] * center[j];
        }
        m.m[i][3] = float(off);
    }
    return m;
}

float turntable_degrees(const AnimationDesc &a, double frame_time) {
    if (!a.turntable) return 0;
    return float(double(a.turntable->degrees) * frame_time / double(a.frames));
}

CameraDesc camera_at(const SceneDesc &scene, double frame_time) {
    CameraDesc c = scene.camera;
    const auto &tt = scene.animation.turntable;
    if (!tt || tt->target != TurntableDesc::Target::camera) return c;
    const Affine m = rotation_about(tt->axis, tt->center,
                                    turntable_degrees(scene.animation, frame_time));
    c.position = m.point(c.position);
    c.look_at = m.point(c.look_at);
    c.up = m.vector(c.up);
    return c;
}

SceneDesc scene_at_frame(const SceneDesc &scene, int frame) {
    SceneDesc s = scene;
    const auto &tt = scene.animation.turntable;
    const double t0 = frame + double(scene.animation.shutter_open);
    s.camera = camera_at(scene, t0);
    if (tt && tt->target == TurntableDesc::Target::object) {
        const Affine m =
            rotation_about(tt->axis, tt->center, turntable_degrees(scene.animation, t0));
        for (ObjectDesc &o : s.objects)
            if (tt->objects.empty() || std::find(tt->objects.begin(), tt->objects.end(),
                                                 o.name) != tt->objects.end())
                o.transform = m * o.transform;
    }
    for (ObjectDesc &o : s.objects) {
        if (o.grow) {
            const int n = scene.animation.frames;
            const double w = n > 1 ? double(frame) / double(n - 1) : 1.0;
            o.grow_age = o.grow->from + (o.grow->to - o.grow->from) * w;
        }
        if (o.clip) {
            const double fps = o.clip->fps > 0 ? o.clip->fps : scene.animation.fps;
            o.clip_seconds =
                clip_time(o.clip->start + t0 / fps, o.clip->duration, o.clip->loop);
            o.clip_motion_seconds.clear();
            if (scene.animation.motion_blur()) {
                // The steps' times are computed from the frame, not from the previous
                // step, so the last step of frame f is the first of frame f + 1 (with
                // the shutter [0, 1]) to the bit.
                const int n = scene.animation.motion_steps;
                const double span =
                    double(scene.animation.shutter_close) - scene.animation.shutter_open;
                for (int k = 0; k < n; ++k) {
                    const double t = k == n - 1
                                         ? frame + double(scene.animation.shutter_close)
                                         : t0 + span * k / (n - 1);
                    o.clip_motion_seconds.push_back(clip_time(
                        o.clip->start + t / fps, o.clip->duration, o.clip->loop));
                }
            }
        }
        if (o.deform.empty()) continue;
        if (o.deform.size() > 1) {
            o.deform_mesh = o.deform[size_t(frame) % o.deform.size()];
            o.deform_weight = 1;
        } else {
            // One pose: from rest at frame 0 to the pose at the last frame.
            const int n = scene.animation.frames;
            o.deform_mesh = o.deform[0];
            o.deform_weight = n > 1 ? float(frame) / float(n - 1) : 1.0f;
        }
    }
    return s;
}

}  // namespace pelage::renderer
