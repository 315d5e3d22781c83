// Property tests of the Chiang et al. 2016 hair BSDF (renderer/bsdf/hair_bsdf.h): white
// furnace, eval/pdf/sample agreement, a chi-square test of sample() against pdf(),
// reciprocity, pigments, parameter validation. Every RNG is seeded; tolerances say why.
#include "renderer/bsdf/hair_bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/bsdf/hair_coat_table.h"
#include "renderer/bsdf/hair_colour_table.h"
#include "renderer/bsdf/hair_furnace.h"
#include "renderer/bsdf/hair_pigments.h"
#include "tests/renderer/bsdf/sphere_chi2.h"

namespace pelage::renderer {
namespace {

constexpr float deg = pi / 180;

struct Rng {
    explicit Rng(uint32_t seed) : gen(seed) {}
    float operator()() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(gen); }
    float in(float a, float b) { return a + (b - a) * (*this)(); }
    // Uniform on the sphere.
    Vec3f direction() {
        const float z = 1 - 2 * (*this)(), r = std::sqrt(std::max(0.0f, 1 - z * z)),
                    phi = 2 * pi * (*this)();
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    std::mt19937 gen;
};

float rel_diff(float a, float b) {
    return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-6f});
}

// --- White furnace ---

// σ_a = 0: ∫ f |cos θ_i| dω_i = 1 for 40 random (β_m, β_n ∈ [0.1, 1], α ∈ [−5°, 5°],
// h ∈ [−1, 1], wo uniform on the sphere), by the 512 × 1024 midpoint quadrature of
// hair_furnace.h. Bound 1e-3, ten times tighter than the required 1 %: the quadrature
// is converged to ~1e-5 at this grid (same value at 256 × 512); the worst case is 4.2e-5.
TEST(HairBsdf, WhiteFurnaceConservesEnergy) {
    Rng rng(20160101);
    float worst = 0;
    for (int k = 0; k < 40; ++k) {
        HairParams p;
        p.beta_m = rng.in(0.1f, 1.0f);
        p.beta_n = rng.in(0.1f, 1.0f);
        p.alpha = rng.in(-5 * deg, 5 * deg);
        const HairBsdf bsdf(p, rng.in(-1, 1));
        const Vec3f wo = rng.direction();
        const FurnaceResult r = furnace_quadrature(bsdf, wo);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(r.f_cos_integral[c] - 1));
            EXPECT_NEAR(r.f_cos_integral[c], 1.0f, 1e-3f)
                << "beta_m " << p.beta_m << " beta_n " << p.beta_n << " alpha " << p.alpha
                << " h " << bsdf.h() << " wo.x " << wo.x;
        }
    }
    RecordProperty("furnace_max_error", std::to_string(worst));
    std::cout << "white furnace: worst |integral - 1| = " << worst
              << " over 40 configurations\n";
}

// The same integral by importance sampling: with σ_a = 0 the lobe weights are exactly A_p
// and each sampled M_p, N_p matches eval, so every weight is 1 (to float rounding: 1e-3).
TEST(HairBsdf, WhiteFurnaceSampleWeightsAreOne) {
    Rng rng(7);
    for (int k = 0; k < 20000; ++k) {
        HairParams p;
        p.beta_m = rng.in(0.1f, 1.0f);
        p.beta_n = rng.in(0.1f, 1.0f);
        p.alpha = rng.in(-5 * deg, 5 * deg);
        const HairBsdf bsdf(p, rng.in(-1, 1));
        const auto s = bsdf.sample(rng.direction(), rng(), rng(), rng());
        if (!s) continue;
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(s->weight[c], 1.0f, 1e-3f) << "sample " << k;
    }
}

// --- eval / pdf / sample agreement ---

TEST(HairBsdf, SampleWeightEqualsEvalCosOverPdf) {
    Rng rng(11);
    int produced = 0;
    for (int k = 0; k < 20000; ++k) {
        HairParams p = HairParams::from_melanin(rng.in(0, 4), rng.in(0, 4),
                                                rng.in(0.1f, 1), rng.in(0.1f, 1));
        p.alpha = rng.in(-5 * deg, 5 * deg);
        const HairBsdf bsdf(p, rng.in(-1, 1));
        const Vec3f wo = rng.direction();
        const auto s = bsdf.sample(wo, rng(), rng(), rng());
        if (!s) continue;
        ++produced;
        const float pdf = bsdf.pdf(wo, s->wi);
        const Rgb f = bsdf.eval(wo, s->wi);
        ASSERT_GT(pdf, 0);
        EXPECT_LT(rel_diff(s->pdf, pdf), 1e-5f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_LT(rel_diff(s->f[c], f[c]), 1e-5f);
            EXPECT_LT(rel_diff(s->weight[c], f[c] * std::abs(s->wi.z) / pdf), 1e-4f);
        }
        EXPECT_NEAR(s->wi.x * s->wi.x + s->wi.y * s->wi.y + s->wi.z * s->wi.z, 1.0f,
                    1e-4f);
    }
    EXPECT_GT(produced, 19900);  // nullopt only at measure-zero wi.z == 0
}

// ∫ pdf dω = 1 for random parameters (absorbing fibres too: lobe weights then differ from
// A_p) by the same quadrature as the furnace, within 1e-3 as the furnace.
TEST(HairBsdf, PdfIntegratesToOne) {
    Rng rng(3);
    for (int k = 0; k < 12; ++k) {
        HairParams p = HairParams::from_melanin(rng.in(0, 3), rng.in(0, 3),
                                                rng.in(0.1f, 1), rng.in(0.1f, 1));
        p.alpha = rng.in(-5 * deg, 5 * deg);
        const HairBsdf bsdf(p, rng.in(-1, 1));
        EXPECT_NEAR(
            furnace_quadrature(bsdf, rng.direction(), 512, 1024, true).pdf_integral, 1.0,
            1e-3)
            << "beta_m " << p.beta_m << " beta_n " << p.beta_n;
    }
}

// Absorbing fibre: the mean sample weight estimates ∫ f|cos| dω; it must match the
// quadrature within 5 standard errors (N = 200 000 samples).
TEST(HairBsdf, MeanSampleWeightMatchesQuadratureAlbedo) {
    Rng rng(5);
    HairParams p = HairParams::from_melanin(1.3f, 0.5f, 0.35f, 0.45f);
    const HairBsdf bsdf(p, 0.3f);
    const Vec3f wo{0.4f, 0.5f, std::sqrt(1 - 0.16f - 0.25f)};
    const Rgb albedo = furnace_quadrature(bsdf, wo).f_cos_integral;
    const int n = 200000;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k) {
        const auto s = bsdf.sample(wo, rng(), rng(), rng());
        if (!s) continue;
        for (int c = 0; c < 3; ++c) {
            sum[c] += s->weight[c];
            sum2[c] += sqr(s->weight[c]);
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, se = std::sqrt((sum2[c] / n - mean * mean) / n);
        EXPECT_NEAR(mean, albedo[c], 5 * se + 1e-4) << "channel " << c;
        EXPECT_LT(albedo[c], 1.0f);
    }
}

// --- Chi-square: sample() against pdf() ---

// Bins: 20 in u = sin θ_i (equal area) × 40 in φ_i; expected counts from the pdf by an
// 8 × 8 midpoint rule per bin (dω = du dφ); bins expecting < 5 are pooled. 10^6 samples
// per case; reject at p < 0.01 / cases (Bonferroni, as Mitsuba's chi2 tests).
TEST(HairBsdf, ChiSquareSampleMatchesPdf) {
    struct Case {
        float beta_m, beta_n, alpha, h, eu;
        Vec3f wo;
    };
    const std::vector<Case> cases = {
        {0.3f, 0.3f, 2 * deg, 0.2f, 0.5f, {0.3f, 0.6f, 0.7416f}},
        {0.5f, 0.6f, -3 * deg, -0.7f, 2.0f, {-0.6f, -0.48f, 0.64f}},
        {0.8f, 0.9f, 2 * deg, 0.95f, 0.0f, {0.0f, 0.0f, 1.0f}},
        {0.25f, 0.5f, 4 * deg, -0.1f, 8.0f, {0.9f, 0.3f, 0.3162f}},
    };
    const int n_samples = 1000000;
    Rng rng(99);
    for (const Case &cs : cases) {
        HairParams p = HairParams::from_melanin(cs.eu, 0.3f, cs.beta_m, cs.beta_n);
        p.alpha = cs.alpha;
        const HairBsdf bsdf(p, cs.h);
        const testing::Chi2Result r = testing::chi2_of_bsdf(bsdf, cs.wo, rng, n_samples);
        const double chi2 = r.chi2, pval = r.p_value;
        const int dof = r.dof;
        std::cout << "chi2: beta_m " << cs.beta_m << " beta_n " << cs.beta_n << ": "
                  << chi2 << " on " << dof << " dof, p = " << pval << "\n";
        EXPECT_GT(pval, 0.01 / cases.size())
            << "beta_m " << cs.beta_m << " beta_n " << cs.beta_n << " chi2 " << chi2
            << " dof " << dof;
    }
}

// --- Reciprocity ---

// M_p is symmetric in (θ_i, θ_o), including the log-space branch (v <= 0.1).
TEST(HairBsdf, LongitudinalScatteringIsSymmetric) {
    Rng rng(17);
    for (int k = 0; k < 10000; ++k) {
        const float ti = rng.in(-pi / 2, pi / 2), to = rng.in(-pi / 2, pi / 2);
        const float v = sqr(rng.in(0.05f, 1.0f));
        const float a = longitudinal_scattering(std::cos(ti), std::cos(to), std::sin(ti),
                                                std::sin(to), v);
        const float b = longitudinal_scattering(std::cos(to), std::cos(ti), std::sin(to),
                                                std::sin(ti), v);
        ASSERT_LT(rel_diff(a, b), 1e-5f) << "v " << v;
    }
}

// The near-field model (fixed h) is reciprocal only up to what the paper's single-angle
// approximations allow: A_p, η' and γ_t use θ_o alone, and N_p is centred on Φ(h). Where
// those agree — cos θ_i = cos θ_o, untilted — swapping wo, wi is the same as mirroring
// h → −h: S(wo, wi; h) = S(wi, wo; −h), S = f·|cos θ_i| (the renderer-facing f divides
// S by the arbitrary |wi.z| of the curve frame; S is what the throughput carries).
// Exact up to float rounding (1e-3 relative, 1e-6 absolute for the near-zero tails).
TEST(HairBsdf, SwappingDirectionsEqualsMirroringHWithoutTilt) {
    Rng rng(23);
    for (int k = 0; k < 20000; ++k) {
        HairParams p = HairParams::from_melanin(rng.in(0, 3), rng.in(0, 3),
                                                rng.in(0.1f, 1), rng.in(0.1f, 1));
        p.alpha = 0;
        const float h = rng.in(-1, 1);
        const HairBsdf fwd(p, h), mirrored(p, -h);
        const Vec3f wo = rng.direction();
        const float sin_i = rng() < 0.5f ? wo.x : -wo.x,
                    cos_i = std::sqrt(std::max(0.0f, 1 - sin_i * sin_i));
        const float phi = rng.in(-pi, pi);
        const Vec3f wi{sin_i, cos_i * std::cos(phi), cos_i * std::sin(phi)};
        const Rgb s_fwd = fwd.eval(wo, wi) * std::abs(wi.z),
                  s_back = mirrored.eval(wi, wo) * std::abs(wo.z);
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(s_fwd[c], s_back[c],
                        1e-3f * std::max(s_fwd[c], s_back[c]) + 1e-6f)
                << "pair " << k;
    }
}

// offset_h's sign agrees with the model: on a cylinder, the mirror reflection of wo about
// the hit normal n has azimuth φ_o + Φ(0) = φ_o − 2 asin(h) (float: 1e-3 rad).
TEST(HairBsdf, OffsetHPutsTheMirrorDirectionOnTheRLobe) {
    Rng rng(41);
    auto dot = [](Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    auto cross = [](Vec3f a, Vec3f b) {
        return Vec3f{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    };
    auto normalize = [&](Vec3f a) { return divide_exactly(a, std::sqrt(dot(a, a))); };
    for (int k = 0; k < 2000; ++k) {
        const Vec3f x = rng.direction();
        const Vec3f n = normalize(cross(x, rng.direction()));
        Vec3f wo = rng.direction();
        if (dot(wo, n) < 0) wo = wo * -1.0f;  // the viewer sees the side n faces
        const float h = offset_h(x, n, wo);
        const Vec3f mirror = n * (2 * dot(wo, n)) - wo;
        // Local frame: x, y = z × x, z = n
        const Vec3f y = cross(n, x);
        auto local = [&](Vec3f w) { return Vec3f{dot(w, x), dot(w, y), dot(w, n)}; };
        const Vec3f lo = local(wo), li = local(mirror);
        if (lo.y * lo.y + lo.z * lo.z < 1e-4f) continue;  // wo nearly along the fibre
        const float dphi = std::atan2(li.z, li.y) - std::atan2(lo.z, lo.y);
        EXPECT_NEAR(std::remainder(dphi + 2 * std::asin(h), 2 * pi), 0.0f, 1e-3f)
            << "case " << k;
        EXPECT_NEAR(li.x, -lo.x, 1e-5f);  // and θ_i = −θ_o, where M_0 peaks (α = 0)
    }
}

// The cuticle scales' free edges point to the tip, so a scale's surface leans out
// towards the tip and its normal towards the root by α: a mirror reflection off it
// leaves at θ_r = −θ_i − 2α. Marschner et al. 2003 ("Light Scattering from Human Hair
// Fibers", SIGGRAPH, §4.1 and Table 1) shift R towards the root and TT, TRT towards the
// tip; Chiang et al. 2016 §4 shift them by −2α, α and 4α. With +x from root to tip
// (hair_bsdf.h), the longitudinal peaks are at θ_i = −θ_o − 2α (R), −θ_o + α (TT) and
// −θ_o + 4α (TRT), as in Cycles' Principled Hair (Chiang); pbrt-v3/v4 rotate θ_o the
// other way and put each peak 4α, 2α, 8α to the other side. Found as the argmax over θ_i
// of S = f·|cos θ_i| at the lobe's own azimuth Φ(p, γ_o, γ_t): at h = 0.9 the lobes lie
// >= 1.9 rad apart and β_n = 0.1 (logistic scale 0.024 rad) leaves the others ~e^-79
// there. β_m = 0.05 (v = 0.0015; TRT 4v) keeps I0's 1/sqrt(x) factor from moving a peak
// by more than v·tan θ_i / 2 < 0.1°. Grid 0.01°, tolerance 0.25° (old code: >= 10°).
TEST(HairBsdf, CuticleTiltShiftsRTowardsTheRootAndTtTrtTowardsTheTip) {
    HairParams p = HairParams::from_melanin(0, 0, 0.05f, 0.1f);
    p.alpha = 5 * deg;
    const float h = 0.9f;
    const HairBsdf bsdf(p, h);
    const float gamma_o = std::asin(h);
    const float shift[3] = {-2 * p.alpha, p.alpha, 4 * p.alpha};
    for (const float theta_o : {-10 * deg, 0.0f, 10 * deg}) {
        const float phi_o = 0.3f;
        const Vec3f wo{std::sin(theta_o), std::cos(theta_o) * std::cos(phi_o),
                       std::cos(theta_o) * std::sin(phi_o)};
        const float etap = std::sqrt(sqr(p.eta) - sqr(wo.x)) / std::cos(theta_o);
        const float gamma_t = std::asin(h / etap);
        for (int lobe = 0; lobe < 3; ++lobe) {
            const float phi_i = phi_o + 2 * lobe * gamma_t - 2 * gamma_o + lobe * pi;
            float best = -1, best_theta = 0;
            for (int k = 0; k <= 17800; ++k) {
                const float theta_i = (-89 + 0.01f * k) * deg;
                const Vec3f wi{std::sin(theta_i), std::cos(theta_i) * std::cos(phi_i),
                               std::cos(theta_i) * std::sin(phi_i)};
                const float s = bsdf.eval(wo, wi).y * std::abs(wi.z);
                if (s > best) best = s, best_theta = theta_i;
            }
            EXPECT_NEAR(best_theta / deg, (-theta_o + shift[lobe]) / deg, 0.25f)
                << "lobe " << lobe << ", theta_o " << theta_o / deg << " degrees";
        }
    }
}

// Low roughness stays finite (the log-space M_p) and sampling still works.
TEST(HairBsdf, LowRoughnessIsFinite) {
    Rng rng(31);
    HairParams p;
    p.beta_m = 0.02f;
    p.beta_n = 0.02f;
    const HairBsdf bsdf(p, 0.4f);
    for (int k = 0; k < 5000; ++k) {
        const Vec3f wo = rng.direction();
        const Rgb f = bsdf.eval(wo, rng.direction());
        ASSERT_TRUE(std::isfinite(f.x) && f.x >= 0);
        const auto s = bsdf.sample(wo, rng(), rng(), rng());
        if (s) {
            ASSERT_TRUE(std::isfinite(s->weight.x) && std::isfinite(s->pdf));
        }
    }
}

// --- Pigments ---

TEST(HairPigments, ZeroMelaninAbsorbsNothing) {
    EXPECT_EQ(sigma_a_from_melanin(0, 0), (Rgb{0, 0, 0}));
    const HairBsdf bsdf(HairParams::from_melanin(0, 0, 0.3f, 0.3f), 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(bsdf.albedo()[c], 1.0f, 1e-5f);
}

TEST(HairPigments, MoreEumelaninIsDarkerAndBluesAbsorbMost) {
    float previous = 2;
    for (float eu : {0.5f, 1.0f, 2.0f, 4.0f, 8.0f}) {
        const Rgb s = sigma_a_from_melanin(eu, 0);
        EXPECT_LT(s.x, s.y);  // red absorbed least: brown-black hair
        EXPECT_LT(s.y, s.z);
        const float a = luminance(
            HairBsdf(HairParams::from_melanin(eu, 0, 0.3f, 0.3f), 0.0f).albedo());
        EXPECT_LT(a, previous) << "eumelanin " << eu;
        previous = a;
    }
}

TEST(HairPigments, ColourRoundTripIsMonotone) {
    const Rgb white = sigma_a_from_colour({1, 1, 1}, 0.3f);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(white[c], 0.0f);
    float previous = 0;
    for (float grey : {0.9f, 0.6f, 0.3f, 0.1f, 0.02f}) {
        const Rgb s = sigma_a_from_colour({grey, grey, grey}, 0.3f);
        EXPECT_GT(s.x, previous) << "colour " << grey;
        EXPECT_EQ(s.x, s.y);
        previous = s.x;
    }
    // A reddish colour absorbs blue most; its single-scattering albedo keeps the hue
    const Rgb red = sigma_a_from_colour({0.6f, 0.3f, 0.1f}, 0.3f);
    EXPECT_LT(red.x, red.y);
    EXPECT_LT(red.y, red.z);
    const Rgb a =
        HairBsdf(HairParams::from_colour({0.6f, 0.3f, 0.1f}, 0.3f, 0.3f), 0.0f).albedo();
    EXPECT_GT(a.x, a.y);
    EXPECT_GT(a.y, a.z);
}

TEST(HairPigments, TheInverseHitsTheMeasuredTableAtItsEntries) {
    // A colour whose slab the table lists gives that entry's σ_a exactly, at a β_n row
    // and between two rows (blended linearly).
    for (size_t i = 0; i < std::size(hair_colour_beta_n); ++i)
        for (size_t k = 0; k < std::size(hair_colour_root_sigma); ++k) {
            const float c = std::exp(-hair_colour_optical[i][k]);
            const float want = sqr(hair_colour_root_sigma[k]);
            EXPECT_NEAR(sigma_a_from_colour({c, c, c}, hair_colour_beta_n[i]).x, want,
                        2e-3f * want)
                << i << " " << k;
        }
    const float mid = 0.5f * (hair_colour_beta_n[2] + hair_colour_beta_n[3]);
    const float f = 0.5f * (hair_colour_optical[2][6] + hair_colour_optical[3][6]);
    EXPECT_NEAR(sigma_a_from_colour({std::exp(-f), 0.5f, 0.5f}, mid).x,
                sqr(hair_colour_root_sigma[6]), 1e-3f);
    // Chiang et al. 2016 §4.2's closed form, from the paper.
    const double d = 5.969 - 0.215 * 0.3 + 2.532 * 0.09 - 10.73 * 0.027 + 5.574 * 0.0081 +
                     0.245 * 0.00243;
    EXPECT_NEAR(sigma_a_from_colour_chiang({0.5f, 0.5f, 0.5f}, 0.3f).x,
                std::pow(std::log(0.5) / d, 2), 1e-6);
}

TEST(HairPigments, TheCoatInverseSolvesTheAddingEquationOfItsTable) {
    // At a table depth and entry, the colour the adding equation A = R + T²·s/(1 − s·R)
    // gives (written here from van de Hulst's form) comes back as that entry's σ_a, over
    // a black, a mid and a light skin. Entries where the measured curves are flat
    // (noise, or T² below the table's floor) have no unique inverse and are skipped.
    constexpr size_t cols = std::size(hair_colour_root_sigma);
    size_t checked = 0;
    for (size_t i = 0; i < std::size(hair_coat_depth); ++i)
        for (size_t k = 1; k < cols; ++k) {
            bool rising = true;
            for (size_t j = 1; j <= k; ++j)
                rising = rising &&
                         hair_coat_reflect[i][j] > hair_coat_reflect[i][j - 1] &&
                         hair_coat_transmit[i][j] > hair_coat_transmit[i][j - 1];
            if (!rising) continue;
            const double r = std::exp(-double(hair_coat_reflect[i][k])),
                         t2 = std::exp(-double(hair_coat_transmit[i][k]));
            for (const float skin : {0.0f, 0.3f, 0.8f}) {
                const float c = float(r + t2 * skin / (1 - skin * r));
                const float want = sqr(hair_colour_root_sigma[k]);
                EXPECT_NEAR(sigma_a_from_coat_colour({c, c, c}, 0.3f, hair_coat_depth[i],
                                                     {skin, skin, skin})
                                .x,
                            want, 1e-3f * want + 1e-6f)
                    << "depth " << hair_coat_depth[i] << " entry " << k << " skin "
                    << skin;
                ++checked;
            }
        }
    EXPECT_GT(checked, 60u);
}

TEST(HairPigments, AThinnerCoatNeedsDarkerFibres) {
    // A dark colour on a skin of that colour: the thinner the coat, the more of the
    // skin shows and the more each fibre must absorb; a deep coat hides the skin.
    const Rgb dark{0.05f, 0.03f, 0.02f};
    float last = 1e9f;
    for (const float depth : {0.7f, 1.5f, 3.0f, 6.0f, 12.0f, 26.0f}) {
        const float s = sigma_a_from_coat_colour(dark, 0.3f, depth, dark).y;
        EXPECT_LT(s, last) << "depth " << depth;
        last = s;
    }
    // What no fibre reaches gets the nearest: a light colour over a dark skin under a
    // thin coat gets clear fibres; a dark one over a white skin the darkest fibres.
    EXPECT_EQ(
        sigma_a_from_coat_colour({0.9f, 0.9f, 0.9f}, 0.3f, 0.5f, {0.05f, 0.05f, 0.05f}).x,
        0.0f);
    EXPECT_EQ(sigma_a_from_coat_colour({0.01f, 0.01f, 0.01f}, 0.3f, 0.5f, {1, 1, 1}).x,
              36.0f);
    // White asks for no absorption at any depth.
    EXPECT_EQ(sigma_a_from_coat_colour({1, 1, 1}, 0.3f, 2, {0.2f, 0.2f, 0.2f}).x, 0.0f);
}

// --- Validation ---

template <typename F>
void expect_invalid(F &&make, const std::string &name) {
    try {
        make();
        ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
}

TEST(HairBsdf, BadParametersThrowFromValidate) {
    const HairParams ok;
    auto with = [&](auto change) {
        HairParams p = ok;
        change(p);
        return p;
    };
    expect_invalid([&] { HairBsdf::validate(ok, 1.5f); }, "h = 1.5");
    expect_invalid([&] { HairBsdf::validate(ok, NAN); }, "h = ");
    expect_invalid(
        [&] { HairBsdf::validate(with([](HairParams &p) { p.beta_m = 0; }), 0); },
        "beta_m = 0");
    expect_invalid(
        [&] { HairBsdf::validate(with([](HairParams &p) { p.beta_m = 1.2f; }), 0); },
        "beta_m = 1.2");
    expect_invalid(
        [&] { HairBsdf::validate(with([](HairParams &p) { p.beta_n = -0.1f; }), 0); },
        "beta_n = -0.1");
    expect_invalid(
        [&] {
            HairBsdf::validate(with([](HairParams &p) { p.sigma_a = {0.1f, -1, 0}; }), 0);
        },
        "sigma_a[1] = -1");
    expect_invalid(
        [&] { HairBsdf::validate(with([](HairParams &p) { p.eta = 0.5f; }), 0); },
        "eta = 0.5");
    expect_invalid(
        [&] { HairBsdf::validate(with([](HairParams &p) { p.alpha = 1; }), 0); },
        "alpha = 1");
    expect_invalid([] { sigma_a_from_melanin(-1, 0); }, "eumelanin = -1");
    expect_invalid([] { sigma_a_from_melanin(0, INFINITY); }, "pheomelanin = inf");
    expect_invalid([] { sigma_a_from_colour({0.5f, 0, 0.5f}, 0.3f); }, "colour[1] = 0");
    expect_invalid(
        [] {
            sigma_a_from_colour({0.5f, 1.5f, 0.5f}, 0.3f);
        },
        "colour[1] = 1.5");
    expect_invalid([] { sigma_a_from_colour({0.5f, 0.5f, 0.5f}, 0); }, "beta_n = 0");
    expect_invalid(
        [] {
            sigma_a_from_coat_colour({0.5f, 0.5f, 0.5f}, 0.3f, -1, {});
        },
        "depth = -1");
    expect_invalid(
        [] {
            sigma_a_from_coat_colour({0.5f, 0.5f, 0.5f}, 0.3f, std::nanf(""), {});
        },
        "depth = nan");
}

// The constructor runs at every strand hit and only DCHECKs validate()'s conditions.
TEST(HairBsdf, ConstructorChecksItsPreconditionInDebugBuilds) {
    EXPECT_TRUE(HairBsdf::invalid(HairParams{}, 0).empty());
    EXPECT_NE(HairBsdf::invalid(HairParams{}, 1.5f).find("h = 1.5"), std::string::npos);
#ifdef NDEBUG
    GTEST_SKIP() << "PELAGE_DCHECK is compiled out with NDEBUG";
#else
    HairParams bad;
    bad.beta_m = 0;
    EXPECT_DEATH(HairBsdf(HairParams{}, 1.5f), "check failed: invalid");
    EXPECT_DEATH(HairBsdf(bad, 0), "check failed: invalid");
#endif
}

}  // namespace
}  // namespace pelage::renderer

// `pelage bench hair` output contract: one JSON object with furnace_max_error.
// A small, fast set (2 fibres, 128 × 256 grid); the error bound is the required 1 %.
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {

TEST(HairBsdf, BenchHairPrintsFurnaceMaxError) {
    std::string out;
    ASSERT_EQ(run_pelage("bench hair --configs 2 --theta-steps 128", &out), 0);
    const auto j = nlohmann::json::parse(out);
    ASSERT_TRUE(j.contains("furnace_max_error"));
    EXPECT_LT(j["furnace_max_error"].get<double>(), 0.01);
    for (const char *k : {"eval_ns", "sample_ns", "pdf_ns", "pdf_integral_max_error"})
        EXPECT_TRUE(j.contains(k)) << k;
}

}  // namespace pelage::test
