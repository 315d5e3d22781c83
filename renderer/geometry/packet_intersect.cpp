#include "renderer/geometry/packet_intersect.h"

#include <algorithm>
#include <limits>

#include "renderer/geometry/embree_ray.h"

namespace pelage::renderer {

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

// Embree's SoA packet types by width, and the call that traces them.
template <int K>
struct Packet;
template <>
struct Packet<4> {
    using Type = RTCRayHit4;
    static void intersect(const int *v, RTCScene s, RTCIntersectContext *c, Type *r) {
        rtcIntersect4(v, s, c, r);
    }
};
template <>
struct Packet<8> {
    using Type = RTCRayHit8;
    static void intersect(const int *v, RTCScene s, RTCIntersectContext *c, Type *r) {
        rtcIntersect8(v, s, c, r);
    }
};
template <>
struct Packet<16> {
    using Type = RTCRayHit16;
    static void intersect(const int *v, RTCScene s, RTCIntersectContext *c, Type *r) {
        rtcIntersect16(v, s, c, r);
    }
};

void set_single(RTCRayHit &rh, Vec3f o, Vec3f d, unsigned id, float time) {
    set_ray(rh.ray, o, d, inf, id, time);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// Rays [0, n), n <= K, as one packet; unused lanes are masked off.
template <int K>
void intersect_packet(RTCScene scene, const Vec3f *o, const Vec3f *d, const unsigned *ids,
                      const float *times, int n, RTCRayHit *out) {
    using P = Packet<K>;
    alignas(64) typename P::Type p;
    alignas(64) int valid[K];
    for (int k = 0; k < K; ++k) {
        const int i = std::min(k, n - 1);  // masked lanes repeat a valid ray
        valid[k] = k < n ? -1 : 0;
        p.ray.org_x[k] = o[i].x;
        p.ray.org_y[k] = o[i].y;
        p.ray.org_z[k] = o[i].z;
        p.ray.tnear[k] = 0;
        p.ray.dir_x[k] = d[i].x;
        p.ray.dir_y[k] = d[i].y;
        p.ray.dir_z[k] = d[i].z;
        p.ray.time[k] = times ? times[i] : 0;
        p.ray.tfar[k] = inf;
        p.ray.mask[k] = 0xffffffffu;
        p.ray.id[k] = ids ? ids[i] : 0;
        p.ray.flags[k] = 0;
        p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    P::intersect(valid, scene, &ctx, &p);
    for (int k = 0; k < n; ++k) {
        RTCRayHit &rh = out[k];
        set_single(rh, o[k], d[k], ids ? ids[k] : 0, times ? times[k] : 0);
        rh.ray.tfar = p.ray.tfar[k];
        rh.hit.geomID = p.hit.geomID[k];
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        rh.hit.primID = p.hit.primID[k];
        rh.hit.instID[0] = p.hit.instID[0][k];
        rh.hit.u = p.hit.u[k];
        rh.hit.v = p.hit.v[k];
        rh.hit.Ng_x = p.hit.Ng_x[k];
        rh.hit.Ng_y = p.hit.Ng_y[k];
        rh.hit.Ng_z = p.hit.Ng_z[k];
    }
}

}  // namespace

PacketIntersector::PacketIntersector(RTCDevice device, RTCScene scene)
    : m_scene(scene), m_width(1) {
    // Only native widths: a width the ISA lacks is emulated one ray at a time.
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
        m_width = 16;
    else if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
        m_width = 8;
    else if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED))
        m_width = 4;
}

void PacketIntersector::intersect(const Vec3f *o, const Vec3f *d, int n, RTCRayHit *out,
                                  const unsigned *ids, const float *times) const {
    for (int i = 0; i < n; i += m_width) {
        const int m = std::min(m_width, n - i);
        switch (m_width) {
            case 16:
                intersect_packet<16>(m_scene, o + i, d + i, ids ? ids + i : nullptr,
                                     times ? times + i : nullptr, m, out + i);
                break;
            case 8:
                intersect_packet<8>(m_scene, o + i, d + i, ids ? ids + i : nullptr,
                                    times ? times + i : nullptr, m, out + i);
                break;
            case 4:
                intersect_packet<4>(m_scene, o + i, d + i, ids ? ids + i : nullptr,
                                    times ? times + i : nullptr, m, out + i);
                break;
            default: {
                RTCIntersectContext ctx;
                rtcInitIntersectContext(&ctx);
                ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                set_single(out[i], o[i], d[i], ids ? ids[i] : 0, times ? times[i] : 0);
                rtcIntersect1(m_scene, &ctx, &out[i]);
            }
        }
    }
}

}  // namespace pelage::renderer
