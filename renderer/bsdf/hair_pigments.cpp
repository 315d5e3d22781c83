// Pigment and colour → σ_a; see hair_pigments.h for the sources.
#include "renderer/bsdf/hair_pigments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "renderer/bsdf/hair_colour_table.h"

namespace pelage::renderer {
namespace {

void check_concentration(const char *name, float c) {
    if (!(std::isfinite(c) && c >= 0))
        throw std::invalid_argument(std::string("hair pigments: ") + name + " = " +
                                    std::to_string(c) +
                                    ": must be a finite concentration >= 0");
}

void check_colour(Rgb colour, float beta_n) {
    if (!(beta_n > 0 && beta_n <= 1))
        throw std::invalid_argument("hair pigments: beta_n = " + std::to_string(beta_n) +
                                    ": must be in (0, 1]");
    for (int c = 0; c < 3; ++c)
        if (!(colour[c] > 0 && colour[c] <= 1))
            throw std::invalid_argument("hair pigments: colour[" + std::to_string(c) +
                                        "] = " + std::to_string(colour[c]) +
                                        ": must be in (0, 1]");
}

// sqrt(σ_a) whose slab has optical depth −ln(albedo) = `target`, at β_n: the table's
// two rows around β_n blended linearly, then the piecewise-linear curve (through 0 at
// σ_a = 0) inverted.
float root_sigma_for(float target, float beta_n) {
    constexpr size_t rows = std::size(hair_colour_beta_n),
                     cols = std::size(hair_colour_root_sigma);
    const float b =
        std::clamp(beta_n, hair_colour_beta_n[0], hair_colour_beta_n[rows - 1]);
    size_t i = 0;
    while (i + 2 < rows && b > hair_colour_beta_n[i + 1]) ++i;
    const float w =
        (b - hair_colour_beta_n[i]) / (hair_colour_beta_n[i + 1] - hair_colour_beta_n[i]);
    float s0 = 0, f0 = 0;  // the curve starts at (0, 0)
    for (size_t k = 0; k < cols; ++k) {
        const float s1 = hair_colour_root_sigma[k];
        // Running maximum: measurement noise never makes the inverse go backwards.
        const float f1 = std::max(
            f0, (1 - w) * hair_colour_optical[i][k] + w * hair_colour_optical[i + 1][k]);
        if (target <= f1 || k + 1 == cols) {
            if (!(f1 > f0)) return s1;
            // Past the last entry the last segment goes on.
            return s0 + (s1 - s0) * (target - f0) / (f1 - f0);
        }
        s0 = s1;
        f0 = f1;
    }
    return s0;
}

}  // namespace

Rgb sigma_a_from_melanin(float eumelanin, float pheomelanin) {
    check_concentration("eumelanin", eumelanin);
    check_concentration("pheomelanin", pheomelanin);
    return eumelanin * eumelanin_sigma_a + pheomelanin * pheomelanin_sigma_a;
}

Rgb sigma_a_from_colour(Rgb colour, float beta_n) {
    check_colour(colour, beta_n);
    auto one = [&](float c) {
        if (c >= 1) return 0.0f;
        return sqr(root_sigma_for(-std::log(c), beta_n));
    };
    return {one(colour.x), one(colour.y), one(colour.z)};
}

Rgb sigma_a_from_colour_chiang(Rgb colour, float beta_n) {
    check_colour(colour, beta_n);
    const float b = beta_n;
    const float denom = 5.969f - 0.215f * b + 2.532f * b * b -
                        10.73f * std::pow(b, 3.0f) + 5.574f * std::pow(b, 4.0f) +
                        0.245f * std::pow(b, 5.0f);
    auto one = [&](float c) { return sqr(std::log(c) / denom); };
    return {one(colour.x), one(colour.y), one(colour.z)};
}

}  // namespace pelage::renderer
