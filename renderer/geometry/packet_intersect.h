// Coherent rays traced together as Embree packets (rtcIntersect4/8/16, the widest the
// device runs natively; Embree tutorials' "coherent" mode). Camera rays
// through neighbouring pixels share most of their BVH traversal: on the cow a 16-ray
// packet costs about a third of tracing its rays one by one (docs/performance.md).
// The hits are handed back one RTCRayHit per ray, exactly what rtcIntersect1 fills, so
// the path loop does not care how its first segment was traced. The grouping depends
// only on pixel positions, never on threads, so images stay bit-identical at any thread
// count.
#pragma once

#include <embree3/rtcore.h>

#include "renderer/core/math.h"

namespace pelage::renderer {

class PacketIntersector {
  public:
    // Rays per intersect() call; split into packets of the device's native width.
    static constexpr int max_rays = 16;

    PacketIntersector(RTCDevice device, RTCScene scene);

    // Native packet width in use: 16, 8, 4, or 1 (no packet support: single rays).
    int width() const { return m_width; }

    // Intersects rays (o[i], d[i]), i < n <= max_rays, over [0, inf), as one coherent
    // batch, each with Embree id ids[i] (0 when ids is null; fur_geometry.h's
    // fur_ray_id()) and time times[i] in the shutter (0 when times is null). out[i]
    // receives ray i and its hit (geomID = RTC_INVALID_GEOMETRY_ID: none).
    void intersect(const Vec3f *o, const Vec3f *d, int n, RTCRayHit *out,
                   const unsigned *ids = nullptr, const float *times = nullptr) const;

  private:
    RTCScene m_scene;
    int m_width;
};

}  // namespace pelage::renderer
