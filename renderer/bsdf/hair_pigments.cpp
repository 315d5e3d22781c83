// Pigment and colour → σ_a; see hair_pigments.h for the sources.
#include "renderer/bsdf/hair_pigments.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pelage::renderer {
namespace {

void check_concentration(const char *name, float c) {
    if (!(std::isfinite(c) && c >= 0))
        throw std::invalid_argument(std::string("hair pigments: ") + name + " = " +
                                    std::to_string(c) +
                                    ": must be a finite concentration >= 0");
}

}  // namespace

Rgb sigma_a_from_melanin(float eumelanin, float pheomelanin) {
    check_concentration("eumelanin", eumelanin);
    check_concentration("pheomelanin", pheomelanin);
    return eumelanin * eumelanin_sigma_a + pheomelanin * pheomelanin_sigma_a;
}

Rgb sigma_a_from_colour(Rgb colour, float beta_n) {
    if (!(beta_n > 0 && beta_n <= 1))
        throw std::invalid_argument("hair pigments: beta_n = " + std::to_string(beta_n) +
                                    ": must be in (0, 1]");
    for (int c = 0; c < 3; ++c)
        if (!(colour[c] > 0 && colour[c] <= 1))
            throw std::invalid_argument("hair pigments: colour[" + std::to_string(c) +
                                        "] = " + std::to_string(colour[c]) +
                                        ": must be in (0, 1]");
    // Chiang et al. 2016 §4.2: σ_a = (ln c / (5.969 − 0.215 β_n + 2.532 β_n² − 10.73 β_n³
    // + 5.574 β_n⁴ + 0.245 β_n⁵))²
    const float b = beta_n;
    const float denom = 5.969f - 0.215f * b + 2.532f * b * b -
                        10.73f * std::pow(b, 3.0f) + 5.574f * std::pow(b, 4.0f) +
                        0.245f * std::pow(b, 5.0f);
    Rgb sigma_a;
    for (int c = 0; c < 3; ++c) {
        const float s = sqr(std::log(colour[c]) / denom);
        (c == 0 ? sigma_a.x : (c == 1 ? sigma_a.y : sigma_a.z)) = s;
    }
    return sigma_a;
}

}  // namespace pelage::renderer
