// Pigment and colour → σ_a; see hair_pigments.h for the sources.
#include "renderer/bsdf/hair_pigments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "renderer/bsdf/hair_coat_table.h"
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

// A coat of one depth at β_n = 0.3, as curves of sqrt(σ_a): −ln R and −ln T² at
// hair_colour_root_sigma, each made non-decreasing (measurement noise never makes a
// darker fibre reflect or transmit more). Between the table's depths both blend
// linearly in ln(depth); below the first, R and T² blend linearly towards a bare skin
// (R = 0, T² = 1 at depth 0); past the last, the last depth's.
struct CoatCurve {
    static constexpr size_t n = std::size(hair_colour_root_sigma);
    float reflect[n], transmit[n];  // −ln R, −ln T²

    explicit CoatCurve(float depth) {
        constexpr size_t rows = std::size(hair_coat_depth);
        auto row = [&](size_t i) {
            for (size_t k = 0; k < n; ++k) {
                reflect[k] = hair_coat_reflect[i][k];
                transmit[k] = hair_coat_transmit[i][k];
            }
        };
        if (depth >= hair_coat_depth[rows - 1]) {
            row(rows - 1);
        } else if (depth <= hair_coat_depth[0]) {
            const float w = std::max(depth, 0.0f) / hair_coat_depth[0];
            for (size_t k = 0; k < n; ++k) {
                const float r = w * std::exp(-hair_coat_reflect[0][k]);
                const float t = 1 - w * (1 - std::exp(-hair_coat_transmit[0][k]));
                reflect[k] = -std::log(std::max(r, 1e-12f));
                transmit[k] = -std::log(std::max(t, 1e-12f));
            }
        } else {
            size_t i = 0;
            while (depth > hair_coat_depth[i + 1]) ++i;
            const float w = std::log(depth / hair_coat_depth[i]) /
                            std::log(hair_coat_depth[i + 1] / hair_coat_depth[i]);
            for (size_t k = 0; k < n; ++k) {
                reflect[k] =
                    (1 - w) * hair_coat_reflect[i][k] + w * hair_coat_reflect[i + 1][k];
                transmit[k] =
                    (1 - w) * hair_coat_transmit[i][k] + w * hair_coat_transmit[i + 1][k];
            }
        }
        for (size_t k = 1; k < n; ++k) {
            reflect[k] = std::max(reflect[k], reflect[k - 1]);
            transmit[k] = std::max(transmit[k], transmit[k - 1]);
        }
    }

    // The curves at sqrt(σ_a) = u: the first entry's value below it (the fibres are
    // clear there), the last segment carried on past the last entry.
    static float at(const float *f, float u) {
        const float *s = hair_colour_root_sigma;
        if (u <= s[0]) return f[0];
        size_t k = 1;
        while (k + 1 < n && u > s[k]) ++k;
        return f[k - 1] + (f[k] - f[k - 1]) * (u - s[k - 1]) / (s[k] - s[k - 1]);
    }

    // The coat's albedo over a skin of albedo `skin`, at sqrt(σ_a) = u.
    float albedo(float u, float skin) const {
        const float r = std::exp(-at(reflect, u)), t2 = std::exp(-at(transmit, u));
        return r + t2 * skin / std::max(1 - skin * r, 1e-6f);
    }
};

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

Rgb sigma_a_from_coat_colour(Rgb colour, float beta_n, float depth, Rgb skin) {
    check_colour(colour, beta_n);
    if (!(std::isfinite(depth) && depth >= 0))
        throw std::invalid_argument("hair pigments: depth = " + std::to_string(depth) +
                                    ": must be a finite number of fibres >= 0");
    const CoatCurve coat(depth);
    // The darkest fibre considered: sqrt(σ_a) = 6, three times the table's last entry.
    constexpr float u_max = 6;
    auto one = [&](float c, float s) {
        if (c >= 1) return 0.0f;
        s = std::isfinite(s) ? std::clamp(s, 0.0f, 1.0f) : 0.0f;
        float lo = 0, hi = u_max;  // albedo(lo) > c >= albedo(hi)
        if (coat.albedo(lo, s) <= c) return 0.0f;
        if (coat.albedo(hi, s) >= c) return sqr(hi);
        // Bisection: the albedo falls monotonically with σ_a; 2^-20 of the range is
        // far below the table's own accuracy.
        for (int it = 0; it < 20; ++it) {
            const float mid = 0.5f * (lo + hi);
            (coat.albedo(mid, s) > c ? lo : hi) = mid;
        }
        const float u = 0.5f * (lo + hi);
        // Other β_n: the thick table's ratio of σ_a between β_n and 0.3.
        const float thick = root_sigma_for(-std::log(c), 0.3f);
        const float ratio = thick > 0 ? root_sigma_for(-std::log(c), beta_n) / thick : 1;
        return sqr(u * ratio);
    };
    return {one(colour.x, skin.x), one(colour.y, skin.y), one(colour.z, skin.z)};
}

}  // namespace pelage::renderer
