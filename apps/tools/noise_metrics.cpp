#include "apps/tools/noise_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pelage::renderer {

std::vector<float> median3x3(const std::vector<float> &pixels, int width, int height,
                             int stride, int channel) {
    std::vector<float> out(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float v[9];
            int k = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = std::clamp(x + dx, 0, width - 1);
                    const int yy = std::clamp(y + dy, 0, height - 1);
                    v[k++] = pixels[(size_t(yy) * width + xx) * stride + channel];
                }
            std::nth_element(v, v + 4, v + 9);
            out[size_t(y) * width + x] = v[4];
        }
    return out;
}

NoiseMetrics measure_noise(const std::vector<float> &image,
                           const std::vector<float> &reference, int width, int height,
                           int stride) {
    const size_t n = size_t(width) * size_t(height);
    if (stride < 4 || image.size() != n * stride || reference.size() != n * stride)
        throw std::invalid_argument("measure_noise: image and reference sizes differ");
    NoiseMetrics m;
    auto on_object = [&](size_t i) { return reference[i * stride + 3] >= 0.5f; };
    double sum = 0, sum_ref = 0, sum_rgb[3] = {0, 0, 0}, sum_ref_rgb[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        if (!on_object(i)) continue;
        ++m.pixels;
        for (int c = 0; c < 3; ++c) {
            const double d = double(image[i * stride + c]) - reference[i * stride + c];
            sum += d * d;
            m.max_error = std::max(m.max_error, std::abs(d));
            sum_ref += reference[i * stride + c];
            sum_rgb[c] += image[i * stride + c];
            sum_ref_rgb[c] += reference[i * stride + c];
            m.reference_max = std::max(m.reference_max, reference[i * stride + c]);
        }
    }
    if (m.pixels == 0) return m;
    m.mse = sum / double(3 * m.pixels);
    m.rmse = std::sqrt(m.mse);
    m.reference_mean = sum_ref / double(3 * m.pixels);
    for (int c = 0; c < 3; ++c) {
        m.mean_rgb[c] = sum_rgb[c] / double(m.pixels);
        m.reference_mean_rgb[c] = sum_ref_rgb[c] / double(m.pixels);
    }
    std::vector<float> brightest(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> med = median3x3(image, width, height, stride, c);
        for (size_t i = 0; i < n; ++i) brightest[i] = std::max(brightest[i], med[i]);
    }
    for (size_t i = 0; i < n; ++i) {
        if (!on_object(i)) continue;
        m.median_max = std::max(m.median_max, brightest[i]);
        if (brightest[i] > m.reference_max) ++m.fireflies;
    }
    return m;
}

}  // namespace pelage::renderer
