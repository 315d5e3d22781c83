// The denoiser's working buffers: the two halves turned into what the filter reads
// (valid-pixel mask, demodulated colour, its variance, the regression features and
// their variance), planar and float so the per-row loops vectorise.
#pragma once

#include <vector>

#include "renderer/denoise/denoise.h"

namespace pelage::renderer::denoise_detail {

// The regression features: albedo RGB, normal XYZ and inverse depth (affine in screen
// coordinates on a plane, and 0 for the sky where depth is +inf).
constexpr int kFeatures = 7;

struct HalfPlanes {
    std::vector<float> colour[3];    // demodulated colour (NaN-free; 0 where invalid)
    std::vector<float> variance[3];  // variance of this half's mean, per channel
};

struct Planes {
    int width = 0, height = 0;
    std::vector<unsigned char> valid;  // both halves have samples and finite colour
    std::vector<float> weight[2];      // each half's share of the pixel's samples
    std::vector<float> modulation[3];  // what the filtered colour is multiplied back by
    std::vector<float> feature[kFeatures];
    std::vector<float> feature_variance[kFeatures];
    HalfPlanes half[2];
    std::vector<float> passthrough;  // RGB interleaved: the mean of what a pixel has
    size_t passed_through = 0, nonfinite = 0;
};

// Checks the sizes (throws std::invalid_argument) and builds the planes.
Planes prepare_planes(const DenoiseInput &input, const DenoiseOptions &options);

// Box mean of `src` over a (2r+1)² square, over valid pixels only (0 where none): a
// direct sum per pixel, so a pixel's value depends only on its own square.
void masked_box_mean(const std::vector<float> &src, const std::vector<unsigned char> &valid,
                     int width, int height, int r, std::vector<float> &dst);

}  // namespace pelage::renderer::denoise_detail
