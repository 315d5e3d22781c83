// From the film's two half buffers to the planes the filter reads: which pixels can be
// trusted, the colour divided by its albedo, and the variances estimated from the
// difference of the halves (NFOR §5.3; Rousselle et al. 2012, dual buffers).
#include "renderer/denoise/denoise_planes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pelage::renderer::denoise_detail {
namespace {

void check_sizes(const DenoiseInput &in) {
    if (in.width < 0 || in.height < 0) {
        throw std::invalid_argument("denoise: negative image size");
    }
    const size_t n = size_t(in.width) * size_t(in.height);
    for (const DenoiseHalf &h : in.half) {
        if (h.colour.size() != 3 * n || h.albedo.size() != 3 * n ||
            h.normal.size() != 3 * n || h.depth.size() != n || h.count.size() != n) {
            throw std::invalid_argument(
                "denoise: a half buffer's size does not match width x height");
        }
    }
}

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.0f; }

float inverse_depth(float z) { return (std::isfinite(z) && z > 1e-6f) ? 1.0f / z : 0.0f; }

}  // namespace

void masked_box_mean(const std::vector<float> &src, const std::vector<unsigned char> &valid,
                     int width, int height, int r, std::vector<float> &dst) {
    // Separable, but each output is a direct sum over its own window (no running sum),
    // so perturbing a pixel outside the window cannot change it by rounding.
    std::vector<float> row_sum(src.size()), row_n(src.size());
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            float s = 0, n = 0;
            for (int i = std::max(0, x - r); i <= std::min(width - 1, x + r); ++i) {
                const size_t j = size_t(y) * width + i;
                s += valid[j] ? src[j] : 0.0f;
                n += valid[j] ? 1.0f : 0.0f;
            }
            row_sum[size_t(y) * width + x] = s;
            row_n[size_t(y) * width + x] = n;
        }
    }
    dst.assign(src.size(), 0.0f);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            float s = 0, n = 0;
            for (int i = std::max(0, y - r); i <= std::min(height - 1, y + r); ++i) {
                s += row_sum[size_t(i) * width + x];
                n += row_n[size_t(i) * width + x];
            }
            dst[size_t(y) * width + x] = n > 0 ? s / n : 0.0f;
        }
    }
}

Planes prepare_planes(const DenoiseInput &in, const DenoiseOptions &opt) {
    check_sizes(in);
    Planes p;
    p.width = in.width;
    p.height = in.height;
    const size_t n = size_t(in.width) * size_t(in.height);
    p.valid.assign(n, 0);
    p.passthrough.assign(3 * n, 0.0f);
    for (auto &w : p.weight) w.assign(n, 0.0f);
    for (auto &m : p.modulation) m.assign(n, 1.0f);
    for (auto &f : p.feature) f.assign(n, 0.0f);
    std::vector<float> raw_var[2][3], raw_fvar[kFeatures];
    for (int h = 0; h < 2; ++h) {
        for (int c = 0; c < 3; ++c) {
            p.half[h].colour[c].assign(n, 0.0f);
            raw_var[h][c].assign(n, 0.0f);
        }
    }
    for (auto &f : raw_fvar) f.assign(n, 0.0f);

    for (size_t i = 0; i < n; ++i) {
        bool usable[2];
        float count[2];
        for (int h = 0; h < 2; ++h) {
            const DenoiseHalf &b = in.half[h];
            bool finite = true;
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(b.colour[3 * i + c])) {
                    finite = false;
                    ++p.nonfinite;
                }
            }
            count[h] = b.count[i];
            usable[h] = finite && std::isfinite(count[h]) && count[h] > 0;
        }
        // A pixel lacking either half has no variance estimate: it keeps the mean of
        // what it has and is never anyone's neighbour.
        const float na = usable[0] ? count[0] : 0.0f, nb = usable[1] ? count[1] : 0.0f;
        if (na + nb > 0) {
            for (int c = 0; c < 3; ++c) {
                float s = 0;
                for (int h = 0; h < 2; ++h) {
                    if (usable[h]) s += (h ? nb : na) * in.half[h].colour[3 * i + c];
                }
                p.passthrough[3 * i + c] = s / (na + nb);
            }
        }
        if (!(usable[0] && usable[1])) {
            ++p.passed_through;
            continue;
        }
        p.valid[i] = 1;
        p.weight[0][i] = na / (na + nb);
        p.weight[1][i] = nb / (na + nb);
        float f[2][kFeatures];
        for (int h = 0; h < 2; ++h) {
            const DenoiseHalf &b = in.half[h];
            for (int c = 0; c < 3; ++c) {
                f[h][c] = std::clamp(finite_or_zero(b.albedo[3 * i + c]), 0.0f, 1.0f);
                f[h][3 + c] = finite_or_zero(b.normal[3 * i + c]);
            }
            f[h][6] = inverse_depth(b.depth[i]);
        }
        for (int k = 0; k < kFeatures; ++k) {
            p.feature[k][i] = p.weight[0][i] * f[0][k] + p.weight[1][i] * f[1][k];
            // The variance of the two halves' mean: E[(a - b)^2] = 2 var(half).
            raw_fvar[k][i] = 0.25f * (f[0][k] - f[1][k]) * (f[0][k] - f[1][k]);
        }
        // Demodulation: the cell pattern lives in the albedo; dividing it out leaves
        // the smooth shading to filter, and multiplying back restores sharp edges.
        for (int c = 0; c < 3; ++c) {
            const float m = opt.demodulate_albedo ? p.feature[c][i] + opt.albedo_epsilon
                                                  : 1.0f;
            p.modulation[c][i] = m;
            const float a = in.half[0].colour[3 * i + c] / m;
            const float b = in.half[1].colour[3 * i + c] / m;
            p.half[0].colour[c][i] = a;
            p.half[1].colour[c][i] = b;
            // var(a - b) = s2 (1/na + 1/nb); half h's mean has variance s2 / n_h.
            const float s2 = (a - b) * (a - b) / (1.0f / na + 1.0f / nb);
            raw_var[0][c][i] = s2 / na;
            raw_var[1][c][i] = s2 / nb;
        }
    }
    // One squared difference is a one-sample estimate; the box mean makes it usable as
    // the normaliser of the distances (Rousselle et al. 2012 smooth it likewise).
    const int r = opt.variance_radius;
    for (int h = 0; h < 2; ++h) {
        for (int c = 0; c < 3; ++c) {
            masked_box_mean(raw_var[h][c], p.valid, p.width, p.height, r,
                            p.half[h].variance[c]);
        }
    }
    for (int k = 0; k < kFeatures; ++k) {
        masked_box_mean(raw_fvar[k], p.valid, p.width, p.height, r,
                        p.feature_variance[k]);
    }
    return p;
}

}  // namespace pelage::renderer::denoise_detail
