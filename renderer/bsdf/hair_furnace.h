// Deterministic sphere quadrature of the hair BSDF, shared by the tests and
// `pelage bench hair`: the white furnace integral ∫ f(wo, wi)|cos θ_i| dω_i (= Σ_p A_p,
// which is 1 for σ_a = 0) and ∫ pdf dω_i (= 1).
//
// Estimator: the midpoint rule on an n_theta × n_phi grid in the fibre's (θ_i, φ_i), with
// dω = cos θ_i dθ_i dφ_i (hair_bsdf.h's frame). The integrand is smooth and φ-periodic,
// so the midpoint rule converges fast once the grid resolves the narrowest lobe: at
// β_m = 0.1 the TT lobe's angular width is ~0.04 rad and at β_n = 0.1 the logistic's
// standard deviation ~0.04 rad, so 512 × 1024 (steps 0.006 rad) is ~6 points per width.
#pragma once

#include "renderer/bsdf/hair_bsdf.h"

namespace pelage::renderer {

struct FurnaceResult {
    Rgb f_cos_integral;   // ∫ f |cos θ_i| dω_i, per channel
    double pdf_integral;  // ∫ pdf dω_i (0 unless with_pdf)
};

FurnaceResult furnace_quadrature(const HairBsdf &bsdf, Vec3f wo, int n_theta = 512,
                                 int n_phi = 1024, bool with_pdf = false);

}  // namespace pelage::renderer
