// A denoiser for Monte Carlo renders from the film's two half buffers: every pixel's
// samples of even index are averaged into half A and those of odd index into half B,
// colour and features alike. The two halves are independent estimates of the same
// pixel, so their difference estimates the variance of the mean even under a
// low-discrepancy sampler, where the samples' own spread overstates it (Rousselle,
// Knaus & Zwicker 2012, "Adaptive Rendering with Non-Local Means Filtering", §5;
// Bitterli et al. 2016, NFOR, §5.3). The filter (nlm_filter.h) weighs each neighbour
// by non-local means on the colour, normalised by that variance, and by the normals'
// and depth's agreement (Rousselle, Manzi & Zwicker 2013, RDFC), on the colour divided
// by the first hit's albedo, so the pattern's cell edges, which are in the albedo, stay
// as sharp as the film has them.
//
// When the halves hold the first hit's light samples apart (`direct`: a sun's light,
// its shadows and the shading of a low-poly mesh's facets, detail no feature holds,
// usually sampled well), those and the rest (sky and bounces: most of the noise,
// smooth where the features are) are filtered apart and added, as production
// denoisers filter light groups and direct and indirect passes apart. A quiet direct
// part keeps its noisy mean (denoise.cpp says when).
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
// `depth` and `count` one. Albedo and normal are means over all the half's
// samples (0 for those that hit nothing); depth is the mean over those that hit.
struct DenoiseHalf {
    std::vector<float> colour;  // the beauty, scene-linear RGB
    // The part of `colour` the first hit's light samples gathered (FilmSample::direct),
    // or empty: then the beauty is filtered whole.
    std::vector<float> direct;
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
    // The filter's window radius in pixels: a (2r+1)² neighbourhood.
    int window_radius = 5;
    // The window of the first hit's light samples, when the halves hold them apart.
    int direct_window_radius = 2;
    // The guide the weights compare is the mean of each (2p+1)² patch, the patch
    // distance of non-local means at a fraction of its cost.
    int patch_radius = 1;
    // Colour bandwidth k (Rousselle et al. 2012, eq. 8): a neighbour whose guide differs
    // by k standard deviations more than its noise explains weighs e⁻¹.
    float k = 1.0f;
    // Albedo difference (RMS over R, G, B) at which a neighbour weighs e⁻¹: a
    // neighbour across a cell edge weighs nothing.
    float albedo_sigma = 0.01f;
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
