// The environment light: a constant radiance, or a lat-long (equirectangular) image
// importance-sampled by luminance × sin θ with a piecewise-constant 2D distribution
// (marginal over rows, conditional within a row; Pharr et al., PBR 3rd ed. §13.6.7 and
// §14.2.4). Direction convention (y up): θ = acos(d.y) from the top row, φ = atan2(d.z,
// d.x) from the left column, then the map is turned by `rotation` degrees about +y.
#pragma once

#include <string>
#include <vector>

#include "renderer/core/math.h"

namespace pelage::renderer {

class EnvironmentLight {
  public:
    EnvironmentLight(Rgb constant);  // constant radiance
    EnvironmentLight(const std::string &image, float scale,
                     float rotation_deg);  // throws

    // Inline for the constant case: it is evaluated at every escaped path and every
    // environment light sample.
    Rgb eval(Vec3f dir) const { return is_constant() ? m_constant : eval_image(dir); }
    float pdf(Vec3f dir) const;  // solid angle
    // Samples a direction; returns its radiance, fills *dir and *pdf.
    Rgb sample(float u1, float u2, Vec3f *dir, float *pdf) const;
    bool is_constant() const { return m_width == 0; }
    // Mean luminance over the sphere of directions (for the light's power).
    float mean_luminance() const {
        return is_constant() ? luminance(m_constant) : m_mean_lum;
    }

  private:
    Rgb eval_image(Vec3f dir) const;
    void direction_to_uv(Vec3f d, float *u, float *v) const;
    Vec3f uv_to_direction(float u, float v) const;

    Rgb m_constant;
    int m_width = 0, m_height = 0;
    std::vector<Rgb> m_pixels;
    std::vector<float> m_marginal_cdf;     // height + 1
    std::vector<float> m_conditional_cdf;  // height × (width + 1)
    std::vector<float> m_pdf;              // per pixel, density in (u, v)
    float m_cos_rot = 1, m_sin_rot = 0;
    float m_mean_lum = 0;
};

}  // namespace pelage::renderer
