// The denoiser's filter: every pixel's colour a weighted mean of its (2r+1)² window,
// with non-local-means weights on a guide image whose distances are normalised by the
// guide's variance (Buades et al. 2005; with the variance cancellation of Rousselle,
// Knaus & Zwicker 2012, §4) and feature weights on normals and depth (Rousselle, Manzi
// & Zwicker 2013, "Robust Denoising using Feature and Color Information", §4). Planar
// float images, row-major; the window's out-of-image and masked pixels take no part. The
// albedo is a feature too: the pattern's cell edges are edges of the albedo, and a
// neighbour across one weighs nothing, so the edges stay as sharp as the film has them.
#pragma once

#include <cstdint>
#include <vector>

namespace pelage::renderer::denoise_detail {

struct Planes {
    int width = 0, height = 0;
    // Per pixel: the values to filter (3 channels), the guide (3) and its variance of
    // the mean (3), the unit normal (3, 0 where none), its variance (1), the depth (1,
    // 0 where none), whether it sees a surface (1 or 0), and whether the pixel may be a
    // neighbour (1) or is kept as it is.
    std::vector<float> value[3], guide[3], guide_var[3], normal[3], normal_var, depth,
        surface;
    std::vector<float> albedo[3], albedo_var;  // the first hit's albedo and its variance
    std::vector<float> value_var;  // the variance of the values' mean (summed over RGB)
    std::vector<uint8_t> usable;
};

// The window and the colour's and albedo's bandwidths are DenoiseOptions' (denoise.h).
struct FilterParams {
    int radius = 0;
    float k = 0;
    float albedo_sigma = 0;
    float normal_sigma = 0.1f;  // 1 − cos of the normals at which a neighbour weighs e⁻¹
    float depth_sigma = 0.02f;  // relative depth difference per pixel of distance
};

// The filtered values (3 planes) and their variance, Σ w² v / (Σ w)² from value_var
// (the weights taken as fixed). Rows run in parallel; each pixel's sums are taken in a
// fixed order, so the result does not depend on the threads.
void nlm_filter(const Planes &in, const FilterParams &params, std::vector<float> out[3],
                std::vector<float> *out_var);

}  // namespace pelage::renderer::denoise_detail
