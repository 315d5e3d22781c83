// Filling one Embree ray: every field Embree reads, so no ray carries a stale value from
// the previous use of its storage (time, mask, flags included).
#pragma once

#include <embree3/rtcore.h>

#include "renderer/core/math.h"

namespace pelage::renderer {

// `time`: the ray's place in the shutter, [0, 1] (moving geometry: embree_scene.h).
inline void set_ray(RTCRay &r, Vec3f o, Vec3f d, float tfar, unsigned id = 0,
                    float time = 0) {
    r.org_x = o.x;
    r.org_y = o.y;
    r.org_z = o.z;
    r.tnear = 0;
    r.dir_x = d.x;
    r.dir_y = d.y;
    r.dir_z = d.z;
    r.time = time;
    r.tfar = tfar;
    r.mask = 0xffffffffu;
    r.id = id;
    r.flags = 0;
}

}  // namespace pelage::renderer
