// The far-field hair BSDF (HairBsdf::FarField, hair_bsdf.h) against the near-field model
// it averages: its mean over the strata's offset ξ is ½ ∫ S(h) dh of the near-field model
// integrated by a fine rule in h, it conserves energy and its pdf integrates to one, its
// samples follow its pdf, and its estimates vary far less than the near-field model's
// at random h (what it is for). Every RNG is seeded; tolerances say why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "renderer/bsdf/hair_bsdf.h"
#include "renderer/bsdf/hair_furnace.h"
#include "tests/renderer/bsdf/sphere_chi2.h"

namespace pelage::renderer {
namespace {

constexpr float deg = pi / 180;

struct Rng {
    explicit Rng(uint32_t seed) : gen(seed) {}
    float operator()() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(gen); }
    float in(float a, float b) { return a + (b - a) * (*this)(); }
    Vec3f direction() {
        const float z = 1 - 2 * (*this)(), r = std::sqrt(std::max(0.0f, 1 - z * z)),
                    phi = 2 * pi * (*this)();
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    std::mt19937 gen;
};

HairParams random_params(Rng &rng) {
    HairParams p = HairParams::from_melanin(rng.in(0, 3), rng.in(0, 3), rng.in(0.1f, 1),
                                            rng.in(0.1f, 1));
    p.alpha = rng.in(-5 * deg, 5 * deg);
    return p;
}

// ½ ∫_{-1}^{1} f(h) dh by the midpoint rule on n points, f the near-field model.
Rgb near_field_average(const HairParams &p, Vec3f wo, Vec3f wi, int n) {
    Rgb sum;
    for (int k = 0; k < n; ++k) {
        const float h = -1 + 2 * (float(k) + 0.5f) / float(n);
        sum += HairBsdf(p, h).eval(wo, wi);
    }
    return sum / float(n);
}

// Averaged over 1 024 stratified ξ, ξ_j = (j + ½) / 1024, the 8-stratum far field puts
// its points at h = −1 + 2(1024 k + j + ½) / 8192: the 8 192-point midpoint rule of the
// near-field model's width average, which it must equal to float rounding (the sums
// run in a different order: 1e-4 relative). Coarser rules differ from it by up to 1.4 %
// where a narrow R lobe sweeps past wi near the silhouettes, so the same points are
// compared, not a converged integral.
TEST(HairFarField, IsTheNearFieldAveragedOverTheWidth) {
    Rng rng(2022);
    for (int k = 0; k < 40; ++k) {
        const HairParams p = random_params(rng);
        const Vec3f wo = rng.direction(), wi = rng.direction();
        const Rgb ref = near_field_average(p, wo, wi, 8192);
        Rgb far;
        for (int j = 0; j < 1024; ++j)
            far +=
                HairBsdf(p, HairBsdf::FarField{8, (float(j) + 0.5f) / 1024}).eval(wo, wi);
        far = far / 1024.0f;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(far[c], ref[c], 1e-4f * std::max(ref[c], 1e-3f))
                << "case " << k << " channel " << c;
    }
}

// σ_a = 0: ∫ f |cos θ_i| dω_i = 1 (the near-field furnace's bound, hair_bsdf_test.cpp),
// and ∫ pdf dω = 1 for absorbing fibres, at any ξ and stratum count.
TEST(HairFarField, ConservesEnergyAndItsPdfIntegratesToOne) {
    Rng rng(16);
    for (int k = 0; k < 8; ++k) {
        HairParams white;
        white.beta_m = rng.in(0.1f, 1.0f);
        white.beta_n = rng.in(0.1f, 1.0f);
        white.alpha = rng.in(-5 * deg, 5 * deg);
        const int nodes = 2 + k;
        const HairBsdf bsdf(white, HairBsdf::FarField{nodes, rng()});
        const FurnaceResult r = furnace_quadrature(bsdf, rng.direction());
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.f_cos_integral[c], 1.0f, 1e-3f);
        const HairBsdf absorbing(random_params(rng), HairBsdf::FarField{nodes, rng()});
        EXPECT_NEAR(
            furnace_quadrature(absorbing, rng.direction(), 512, 1024, true).pdf_integral,
            1.0, 1e-3);
    }
}

// sample() returns f, pdf and weight that eval and pdf agree with.
TEST(HairFarField, SampleWeightEqualsEvalCosOverPdf) {
    Rng rng(12);
    int produced = 0;
    for (int k = 0; k < 5000; ++k) {
        const HairBsdf bsdf(random_params(rng), HairBsdf::FarField{8, rng()});
        const Vec3f wo = rng.direction();
        const auto s = bsdf.sample(wo, rng(), rng(), rng());
        if (!s) continue;
        ++produced;
        float pdf;
        const Rgb f = bsdf.eval_pdf(wo, s->wi, &pdf);
        ASSERT_GT(pdf, 0);
        EXPECT_NEAR(s->pdf, pdf, 1e-5f * pdf);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(s->weight[c], f[c] * std::abs(s->wi.z) / pdf,
                        1e-4f * std::max(s->weight[c], 1e-3f));
    }
    EXPECT_GT(produced, 4950);
}

// Chi-square of sample() against pdf() (as hair_bsdf_test.cpp's near-field test: 20 × 40
// equal-area bins, bins expecting < 5 pooled, 10^6 samples, p < 0.01 / cases rejects).
TEST(HairFarField, ChiSquareSampleMatchesPdf) {
    struct Case {
        float beta_m, beta_n, xi;
        Vec3f wo;
    };
    const std::vector<Case> cases = {{0.3f, 0.3f, 0.37f, {0.3f, 0.6f, 0.7416f}},
                                     {0.6f, 0.2f, 0.91f, {-0.6f, -0.48f, 0.64f}}};
    const int n_samples = 1000000;
    Rng rng(1998);
    for (const Case &cs : cases) {
        HairParams p = HairParams::from_melanin(0.8f, 1.5f, cs.beta_m, cs.beta_n);
        p.alpha = 2 * deg;
        const HairBsdf bsdf(p, HairBsdf::FarField{8, cs.xi});
        const testing::Chi2Result r =
            testing::chi2_of_bsdf(bsdf, cs.wo, rng, n_samples, 6);
        const double chi2 = r.chi2, pval = r.p_value;
        const int dof = r.dof;
        EXPECT_GT(pval, 0.01 / cases.size()) << "chi2 " << chi2 << " dof " << dof;
    }
}

// What the far field is for: for dark fibres lit by light from one direction, the
// near-field value at a uniformly random h (a sub-pixel strand's sample) has a relative
// variance dominated by R's Fresnel spike at the silhouettes; the 8-stratum far field at
// a random ξ has the same mean and at most a fifth of that variance (a tenth and less
// is measured).
TEST(HairFarField, VariesFarLessThanTheNearFieldAtRandomH) {
    Rng rng(7);
    const HairParams p = HairParams::from_melanin(3.0f, 0.5f, 0.3f, 0.3f);
    const Vec3f wo = normalize(Vec3f{0.2f, 0.3f, 0.93f});
    const int n = 20000;
    for (const Vec3f wi :
         {normalize(Vec3f{-0.3f, 0.8f, 0.5f}), normalize(Vec3f{0.1f, -0.2f, -0.97f})}) {
        double near_sum = 0, near_sq = 0, far_sum = 0, far_sq = 0;
        for (int k = 0; k < n; ++k) {
            const float ln = HairBsdf(p, rng.in(-1, 1)).eval(wo, wi).y;
            const float lf = HairBsdf(p, HairBsdf::FarField{8, rng()}).eval(wo, wi).y;
            near_sum += ln, near_sq += double(ln) * ln;
            far_sum += lf, far_sq += double(lf) * lf;
        }
        const double near_mean = near_sum / n, far_mean = far_sum / n;
        const double near_var = near_sq / n - near_mean * near_mean;
        const double far_var = far_sq / n - far_mean * far_mean;
        EXPECT_NEAR(far_mean, near_mean, 4 * std::sqrt(near_var / n));
        EXPECT_LT(far_var, near_var / 5) << "near " << near_var << " far " << far_var;
    }
}

}  // namespace
}  // namespace pelage::renderer
