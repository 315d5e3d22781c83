// Pinhole and thin-lens cameras. Raster space: x right, y down, pixel (i, j) covers
// [i, i+1) × [j, j+1). The vertical field of view spans the image height.
#pragma once

#include <array>

#include "renderer/core/math.h"
#include "renderer/scene_frame/scene_frame.h"

namespace pelage::renderer {

struct CameraRay {
    Vec3f o, d;       // d unit length
    Vec3f forward{};  // the viewing direction of the camera that made it (depth AOV)
};

class Camera {
  public:
    Camera(const CameraDesc &desc, int width, int height);

    // A ray through raster position (x, y); (u1, u2) pick the point on the lens.
    CameraRay generate(float x, float y, float u1, float u2) const;
    Vec3f forward() const { return m_w; }
    // False for a pinhole: generate() then ignores (u1, u2).
    bool has_lens() const { return m_lens_radius > 0; }

    // 4×4 matrices as OpenEXR's worldToCamera and worldToNDC attributes store them
    // (Imath's row vectors: p' = p · M, row-major). Camera space is right-handed, x
    // right, y up, looking down −z. NDC is pbrt-v4's: x, y in [0, 1] across the image
    // from its bottom-left corner, after the division by w, and z = 1 / depth.
    std::array<float, 16> world_to_camera() const;
    std::array<float, 16> world_to_ndc() const;

  private:
    Vec3f m_pos, m_u, m_v, m_w;  // right, up, forward
    float m_tan_half_h, m_aspect, m_lens_radius, m_focus;
    float m_scale_x, m_scale_y;  // raster → image plane
};

// Camera motion blur over a camera turntable's shutter: the camera at shutter position
// u in [0, 1) is the scene's camera at frame time open + span·u (camera_at). A plain
// value, so each sample's camera is a direct call.
struct CameraMotion {
    const SceneDesc *scene = nullptr;
    double open = 0, span = 0;  // in frames

    Camera at(float u, int width, int height) const {
        return Camera(camera_at(*scene, open + span * double(u)), width, height);
    }
};

}  // namespace pelage::renderer
