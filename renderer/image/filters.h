// Pixel reconstruction filters (box, Gaussian, Blackman-Harris), all separable:
// f(dx, dy) = f1(dx) f1(dy) over [-radius, radius]². Each pixel is the filter-weighted
// mean of its own samples: sample offsets are drawn from the filter itself (a 1D table of
// f1, piecewise constant over 256 bins, its inverse tabulated at 1024 points), so every
// sample has weight 1 and no pixel ever receives another tile's samples (images do not
// depend on scheduling). The tabulation is the only approximation: the filter becomes a
// 256-step staircase.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

class PixelFilter {
  public:
    PixelFilter(FilterType type, float radius) : m_type(type), m_radius(radius) {
        // Gaussian: σ = radius / 3, shifted so it reaches 0 at the radius.
        m_alpha = 1.0f / (2 * (radius / 3) * (radius / 3));
        m_edge = std::exp(-m_alpha * radius * radius);
        m_cdf.resize(bins + 1, 0.0f);
        for (int i = 0; i < bins; ++i)
            m_cdf[i + 1] =
                m_cdf[i] +
                std::max(0.0f, eval_1d(-radius + (i + 0.5f) * 2 * radius / bins));
        for (float &c : m_cdf) c /= m_cdf[bins];
        // Tabulate the inverse CDF at evenly spaced u, so sampling is one lookup and a
        // lerp (a binary search per sample cost as much as a ray).
        m_inverse.resize(inverse_bins + 1);
        for (int k = 0; k <= inverse_bins; ++k)
            m_inverse[k] = invert(float(k) / inverse_bins);
    }
    float radius() const { return m_radius; }

    // An offset in [-radius, radius] distributed like f1, from u in [0, 1).
    float sample_1d(float u) const {
        if (m_type == FilterType::box) return (2 * u - 1) * m_radius;
        const float x = u * inverse_bins;
        const int k = std::min(int(x), inverse_bins - 1);
        return m_inverse[k] + (x - k) * (m_inverse[k + 1] - m_inverse[k]);
    }

  private:
    float invert(float u) const {
        const int i = std::clamp(
            int(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin()) - 1, 0,
            bins - 1);
        const float w = m_cdf[i + 1] - m_cdf[i];
        const float t = w > 0 ? (u - m_cdf[i]) / w : 0.5f;
        return std::clamp(-m_radius + (i + t) * (2 * m_radius / bins), -m_radius,
                          m_radius);
    }

  public:
    float eval_1d(float d) const {
        if (std::abs(d) > m_radius) return 0.0f;
        switch (m_type) {
            case FilterType::box:
                return 1.0f;
            case FilterType::gaussian:
                return std::max(0.0f, std::exp(-m_alpha * d * d) - m_edge);
            case FilterType::blackman_harris: {
                // Blackman-Harris window (Harris 1978, "On the use of windows for
                // harmonic analysis with the discrete Fourier transform", Proc. IEEE
                // 66(1), 4-term coefficients), stretched over [-radius, radius].
                const float x = 2 * 3.14159265358979f * (d / (2 * m_radius) + 0.5f);
                return 0.35875f - 0.48829f * std::cos(x) + 0.14128f * std::cos(2 * x) -
                       0.01168f * std::cos(3 * x);
            }
        }
        return 0.0f;
    }

  private:
    static constexpr int bins = 256, inverse_bins = 1024;
    FilterType m_type;
    float m_radius, m_alpha = 0, m_edge = 0;
    std::vector<float> m_cdf, m_inverse;
};

}  // namespace pelage::renderer
