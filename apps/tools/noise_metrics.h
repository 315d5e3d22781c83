// How far a render is from a converged reference of the same scene: the error a user
// sees, measured over the pixels the scene's objects cover (`pelage bench noise`).
//   * MSE: the mean over those pixels and the R, G, B channels of
//     (image − reference)², in scene-linear values; RMSE its square root. For an
//     unbiased renderer the MSE is the variance of the pixel estimates (plus the
//     reference's own, smaller by the ratio of the sample counts).
//   * Fireflies: object pixels whose 3×3 median (per channel) still exceeds the
//     brightest value of the reference anywhere on the objects. A median removes
//     isolated outliers of ordinary noise; what survives it is a cluster of samples
//     brighter than anything the converged image holds.
//   * Worst pixel: the largest |image − reference| of any channel of any object pixel,
//     over the reference's mean (max_error_over_mean): how far the worst outlier is from
//     the converged value, in units of the image's brightness.
// A pixel belongs to the objects when the reference's coverage (alpha) is at least 1/2.
#pragma once

#include <cstddef>
#include <vector>

namespace pelage::renderer {

struct NoiseMetrics {
    double mse = 0, rmse = 0;
    double reference_mean = 0;  // of the objects' R, G, B: rmse / it is a relative error
    // The image's and the reference's mean per channel over the same pixels: their ratio
    // is the image's bias when both are converged (e.g. a prefilter against none).
    double mean_rgb[3] = {0, 0, 0}, reference_mean_rgb[3] = {0, 0, 0};
    size_t pixels = 0;        // object pixels measured
    size_t fireflies = 0;     // object pixels above the reference's maximum
    float reference_max = 0;  // brightest channel value of the reference's objects
    float median_max = 0;     // ... and of the image after the 3×3 median
    double max_error = 0;     // the largest |image − reference| of one channel
    double max_error_over_mean() const {
        return reference_mean > 0 ? max_error / reference_mean : 0.0;
    }
};

// `image` and `reference`: width × height pixels of `stride` interleaved floats each,
// R, G, B first; the reference's channel 3 is its coverage.
NoiseMetrics measure_noise(const std::vector<float> &image,
                           const std::vector<float> &reference, int width, int height,
                           int stride);

// The 3×3 median of channel `channel`, the border clamped (a test hook).
std::vector<float> median3x3(const std::vector<float> &pixels, int width, int height,
                             int stride, int channel);

}  // namespace pelage::renderer
