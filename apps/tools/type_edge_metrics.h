// Whether a denoised (or otherwise filtered) render keeps the pattern where it is: the
// error against a converged reference, per cell type, as a function of the distance to
// the nearest edge between two types (`pelage bench noise --denoise`).
//   * Bias: over a type's pixels at least `interior` pixels from any type edge, the
//     image's mean over the reference's mean, minus 1.
//   * Halo: a filter that blurs across an edge brightens the dark side and darkens the
//     light side, each in a band as wide as its blur. Per type and Chebyshev distance d
//     from the nearest pixel of another type, the mean signed error relative to the
//     reference's mean there; the halo is the largest d ≥ 1 at which some type's
//     error exceeds `tolerance` (0 when none does). Buckets of fewer than `min_pixels`
//     are not judged: their mean is noise.
// Types come per pixel from the render's cell_type AOV (−1 where none): sample 0's, so
// an edge pixel's type is one of the two; distances are measured to those pixels.
#pragma once

#include <cstddef>
#include <vector>

namespace pelage::renderer {

struct TypeEdgeMetrics {
    struct Type {
        int type = 0;
        size_t interior_pixels = 0;
        double mean = 0, reference_mean = 0, bias = 0;
        // Signed relative error at distance 0, 1, ... from the edge, and its pixels.
        std::vector<double> error_by_distance;
        std::vector<size_t> pixels_by_distance;
    };
    std::vector<Type> types;
    int halo_pixels = 0;
    double max_bias = 0;  // the largest |bias| of a type
};

// `image` and `reference`: width × height pixels of `stride` floats, R, G, B first;
// `types`: one value per pixel.
TypeEdgeMetrics measure_type_edges(const std::vector<float> &image,
                                   const std::vector<float> &reference,
                                   const std::vector<float> &types, int width, int height,
                                   int stride, int interior = 4, int max_distance = 8,
                                   double tolerance = 0.02, size_t min_pixels = 200);

}  // namespace pelage::renderer
