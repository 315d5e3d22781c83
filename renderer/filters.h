// Pixel reconstruction filters, evaluated at an offset (dx, dy) in pixels from the pixel
// centre; zero outside the radius. Each pixel is the filter-weighted mean of its own
// samples (samples are spread over the filter's support), so no pixel ever receives
// another tile's samples and images do not depend on scheduling.
#pragma once

#include <cmath>

#include "renderer/scene_file.h"

namespace pelage::renderer {

class PixelFilter {
  public:
    PixelFilter(FilterType type, float radius) : m_type(type), m_radius(radius) {
        // Gaussian: σ = radius / 3, shifted so it reaches 0 at the radius.
        m_alpha = 1.0f / (2 * sqr(radius / 3));
        m_edge = std::exp(-m_alpha * radius * radius);
    }
    float radius() const { return m_radius; }
    float eval(float dx, float dy) const {
        if (std::abs(dx) > m_radius || std::abs(dy) > m_radius) return 0.0f;
        switch (m_type) {
            case FilterType::box: return 1.0f;
            case FilterType::gaussian: return gaussian(dx) * gaussian(dy);
            case FilterType::blackman_harris: return blackman_harris(dx) * blackman_harris(dy);
        }
        return 0.0f;
    }

  private:
    float gaussian(float d) const { return std::max(0.0f, std::exp(-m_alpha * d * d) - m_edge); }
    // Blackman-Harris window (Harris 1978, "On the use of windows for harmonic analysis
    // with the discrete Fourier transform", Proc. IEEE 66(1), 4-term coefficients),
    // stretched over [-radius, radius].
    float blackman_harris(float d) const {
        const float x = 2 * pi * (d / (2 * m_radius) + 0.5f);
        return 0.35875f - 0.48829f * std::cos(x) + 0.14128f * std::cos(2 * x) - 0.01168f * std::cos(3 * x);
    }
    static float sqr(float x) { return x * x; }

    FilterType m_type;
    float m_radius, m_alpha = 0, m_edge = 0;
};

}  // namespace pelage::renderer
