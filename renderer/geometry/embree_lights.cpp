// Area lights as Embree geometry: a quad light is one RTC_GEOMETRY_TYPE_QUAD, a sphere
// light one RTC_GEOMETRY_TYPE_SPHERE_POINT (Embree intersects both the near and, from
// inside, the far side of a sphere). Their buffers are Embree's own
// (rtcSetNewGeometryBuffer): a light is a handful of floats, not worth sharing.
#include <string>

#include "renderer/geometry/embree_scene.h"

namespace pelage::renderer {

void EmbreeScene::attach_area_lights(const std::vector<LightDesc> &lights) {
    for (size_t i = 0; i < lights.size(); ++i) {
        const LightDesc &l = lights[i];
        RTCGeometry g = nullptr;
        if (l.type == LightDesc::Type::quad) {
            g = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_QUAD);
            auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
            const Vec3f c[4] = {l.corner, l.corner + l.edge_u,
                                l.corner + l.edge_u + l.edge_v, l.corner + l.edge_v};
            for (int k = 0; k < 4; ++k) {
                v[3 * k] = c[k].x;
                v[3 * k + 1] = c[k].y;
                v[3 * k + 2] = c[k].z;
            }
            auto *q = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(uint32_t), 1));
            for (uint32_t k = 0; k < 4; ++k) q[k] = k;
        } else if (l.type == LightDesc::Type::sphere) {
            g = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
            v[0] = l.center.x;
            v[1] = l.center.y;
            v[2] = l.center.z;
            v[3] = l.radius;
        } else {
            continue;  // environment and distant lights are at infinity
        }
        rtcCommitGeometry(g);
        const unsigned id = rtcAttachGeometry(m_scene, g);
        rtcReleaseGeometry(g);
        if (m_light_of_geometry.size() <= id) m_light_of_geometry.resize(id + 1, -1);
        m_light_of_geometry[id] = int(i);
    }
}

}  // namespace pelage::renderer
