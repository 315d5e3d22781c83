#include "renderer/camera/camera.h"

#include <cmath>

#include "renderer/core/sampling.h"

namespace pelage::renderer {

Camera::Camera(const CameraDesc &d, int width, int height) : m_pos(d.position) {
    m_w = normalize(d.look_at - d.position);
    m_u = normalize(cross(m_w, d.up));
    m_v = cross(m_u, m_w);
    m_tan_half_h = std::tan(0.5f * d.fov_deg * pi / 180);
    m_aspect = float(width) / float(height);
    m_lens_radius = d.type == CameraDesc::Type::thin_lens ? d.aperture_radius : 0.0f;
    m_focus = d.focus_distance > 0 ? d.focus_distance : length(d.look_at - d.position);
    m_scale_x = 2.0f / width * m_tan_half_h * m_aspect;
    m_scale_y = 2.0f / height * m_tan_half_h;
}

CameraRay Camera::generate(float x, float y, float u1, float u2) const {
    // Point on the image plane at distance 1 in camera space.
    const float sx = x * m_scale_x - m_tan_half_h * m_aspect;
    const float sy = m_tan_half_h - y * m_scale_y;
    Vec3f dir = m_u * sx + m_v * sy + m_w;
    if (m_lens_radius <= 0) return {m_pos, normalize(dir), m_w};
    // --- Thin lens: aim from a lens point at the in-focus point ---
    float lx, ly;
    sample_disk(u1, u2, &lx, &ly);
    const Vec3f lens = m_u * (lx * m_lens_radius) + m_v * (ly * m_lens_radius);
    const Vec3f focus = dir * m_focus;  // the focus plane is at depth m_focus along m_w
    return {m_pos + lens, normalize(focus - lens), m_w};
}

std::array<float, 16> Camera::world_to_camera() const {
    const Vec3f axis[3] = {m_u, m_v, -m_w};
    std::array<float, 16> m{};
    for (int j = 0; j < 3; ++j) {
        m[0 * 4 + j] = axis[j].x;
        m[1 * 4 + j] = axis[j].y;
        m[2 * 4 + j] = axis[j].z;
        m[3 * 4 + j] = -dot(m_pos, axis[j]);
    }
    m[15] = 1;
    return m;
}

std::array<float, 16> Camera::world_to_ndc() const {
    // Camera → NDC: w' = depth = −z; x' = x / (2 tan(fov/2) aspect) + w'/2, and
    // likewise y', so x'/w' runs 0 → 1 across the image; z' = 1.
    std::array<float, 16> c{};
    c[0 * 4 + 0] = 0.5f / (m_tan_half_h * m_aspect);
    c[1 * 4 + 1] = 0.5f / m_tan_half_h;
    c[2 * 4 + 0] = -0.5f;
    c[2 * 4 + 1] = -0.5f;
    c[2 * 4 + 3] = -1.0f;
    c[3 * 4 + 2] = 1.0f;
    const std::array<float, 16> w = world_to_camera();
    std::array<float, 16> m{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) m[i * 4 + j] += w[i * 4 + k] * c[k * 4 + j];
    return m;
}

}  // namespace pelage::renderer
