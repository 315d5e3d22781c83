// A chi-square test of a sampler against its density over the sphere, shared by the hair
// BSDF tests (hair_bsdf_test.cpp, hair_far_field_test.cpp). Bins: nu in u = x (the
// fibre's axis, equal area) × nphi in φ = atan2(z, y); the expected count of each bin is
// the pdf integrated by a sub × sub midpoint rule (dω = du dφ); bins expecting < 5 are
// pooled into one, as Mitsuba's chi2 tests do.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "sim/core/vec.h"

namespace pelage::renderer::testing {

struct Chi2Result {
    double chi2 = 0, p_value = 0;
    int dof = 0;
};

// Wilson–Hilferty: P(χ²_k >= x) via the normal approximation of (χ²/k)^(1/3), accurate
// to ~1e-3 in p for the k of hundreds used here.
inline double chi2_p_value(double x, int k) {
    const double m = 1 - 2.0 / (9 * k), sd = std::sqrt(2.0 / (9 * k));
    const double z = (std::cbrt(x / k) - m) / sd;
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// pdf(wi) → the density in solid angle; sample() → std::optional<Vec3f> of a direction
// (nullopt: no sample, which counts against no bin but is still one of n_samples).
template <class Pdf, class Sample>
Chi2Result chi2_sample_vs_pdf(Pdf &&pdf, Sample &&sample, int n_samples, int nu = 20,
                              int nphi = 40, int sub = 8) {
    std::vector<double> expected(size_t(nu) * nphi, 0.0), observed(expected.size(), 0.0);
    const double du = 2.0 / nu, dphi = 2 * M_PI / nphi;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nphi; ++j) {
            double acc = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double u = -1 + (i + (a + 0.5) / sub) * du;
                    const double phi = -M_PI + (j + (b + 0.5) / sub) * dphi;
                    const double r = std::sqrt(std::max(0.0, 1 - u * u));
                    acc += pdf(Vec3f{float(u), float(r * std::cos(phi)),
                                     float(r * std::sin(phi))});
                }
            expected[size_t(i) * nphi + j] = acc * du * dphi / (sub * sub) * n_samples;
        }
    for (int k = 0; k < n_samples; ++k) {
        const std::optional<Vec3f> wi = sample();
        if (!wi) continue;
        const int i = std::clamp(int((wi->x + 1) / du), 0, nu - 1);
        const int j =
            std::clamp(int((std::atan2(wi->z, wi->y) + M_PI) / dphi), 0, nphi - 1);
        observed[size_t(i) * nphi + j] += 1;
    }
    Chi2Result r;
    double pooled_e = 0, pooled_o = 0;
    for (size_t b = 0; b < expected.size(); ++b) {
        if (expected[b] < 5) {
            pooled_e += expected[b];
            pooled_o += observed[b];
            continue;
        }
        r.chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++r.dof;
    }
    if (pooled_e > 0) {
        r.chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / std::max(pooled_e, 5.0);
        ++r.dof;
    }
    r.dof -= 1;
    r.p_value = chi2_p_value(r.chi2, r.dof);
    return r;
}

// The test of a BSDF's sample() against its pdf() for the outgoing direction wo, with
// three uniform numbers from rng() per sample.
template <class Bsdf, class Rng>
Chi2Result chi2_of_bsdf(const Bsdf &bsdf, Vec3f wo, Rng &rng, int n_samples,
                        int sub = 8) {
    return chi2_sample_vs_pdf([&](Vec3f wi) { return bsdf.pdf(wo, wi); },
                              [&]() -> std::optional<Vec3f> {
                                  const auto s = bsdf.sample(wo, rng(), rng(), rng());
                                  if (!s) return std::nullopt;
                                  return s->wi;
                              },
                              n_samples, 20, 40, sub);
}

}  // namespace pelage::renderer::testing
