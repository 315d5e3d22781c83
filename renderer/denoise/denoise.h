// A denoiser for Monte Carlo renders from the film's two half buffers: every pixel's
// samples of even index are averaged into half A and those of odd index into half B,
// colour and features alike. The two halves are independent estimates of the same
// pixel, so their difference estimates the variance of the mean even under a
// low-discrepancy sampler (Bitterli et al. 2016, "Nonlinearly Weighted First-order
// Regression for Denoising Monte Carlo Renderings", §5.3; Rousselle, Manzi & Zwicker
// 2012 for the dual-buffer idea), and filtering one half with weights taken from the
// other keeps the weights uncorrelated with the noise they filter (NFOR §4.3).
//
// The output of a pixel depends only on inputs within support_radius() pixels of it,
// so a band of a still (`--tile I/N`) rendered with that margin denoises to the same
// bytes as the whole image. Rows are filtered in parallel and every pixel's arithmetic
// is fixed, so the result is the same at any thread count.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer {

// One half buffer: per pixel, the means of that half's samples. Planar, row-major,
// width × height pixels; `colour`, `albedo` and `normal` hold 3 floats per pixel,
// `depth` and `count` one.
struct DenoiseHalf {
    std::vector<float> colour;  // the beauty, scene-linear RGB
    std::vector<float> albedo;  // first-hit albedo (0 where no surface)
    std::vector<float> normal;  // first-hit world-space shading normal (0 where none)
    std::vector<float> depth;   // first-hit camera depth; +inf where no surface
    std::vector<float> count;   // samples in this half (its weight sum)
};

struct DenoiseInput {
    int width = 0, height = 0;
    DenoiseHalf half[2];
};

struct DenoiseOptions {
    // Filter window radius in pixels (a (2r+1)² neighbourhood) and the NL-means patch
    // radius of the colour weights (NFOR §4.2 uses 9 and 3).
    int window_radius = 7;
    int patch_radius = 3;
};

struct DenoiseStats {
    size_t pixels_passed_through = 0;  // pixels with no usable statistics, kept noisy
    size_t nonfinite_inputs = 0;       // NaN or infinite colour values found
    double seconds = 0;
};

// Pixels within this distance of an output pixel are the only ones it reads.
int denoise_support_radius(const DenoiseOptions &options);

// The denoised beauty, RGB interleaved, width × height × 3. Throws std::invalid_argument
// when the buffers' sizes do not match width × height. A pixel without samples in one
// half, or with non-finite values, is passed through as the mean of what it has
// (counted in `stats`), never propagated to its neighbours.
std::vector<float> denoise(const DenoiseInput &input, const DenoiseOptions &options = {},
                           DenoiseStats *stats = nullptr);

}  // namespace pelage::renderer
