// Absorption coefficients σ_a for the hair BSDF (hair_bsdf.h), from pigment or from
// colour.
//
//  * Melanin: σ_a = c_eu·σ_eu + c_pheo·σ_pheo with the eumelanin and pheomelanin
//  absorption
//    spectra of d'Eon, Francois, Hill, Letteri, Aubry 2011, "An Energy-Conserving Hair
//    Reflectance Model", Computer Graphics Forum 30(4):1181–1187,
//    doi:10.1111/j.1467-8659.2011.01976.x (RGB values as used by pbrt-v3/v4 and Cycles).
//    Concentrations are dimensionless (0 = no pigment; about 8 is black hair).
//  * Colour: Chiang, Bitterli, Tappan, Burley 2016 (doi:10.1111/cgf.12830) §4.2 fit a
//    polynomial in β_n so that a fibre with that σ_a, in a coat of many fibres, looks
//    like the target colour after multiple scattering.
//
// σ_a is per fibre radius: the BSDF's transmittance uses the chord 2·cos γ_t of a
// unit-radius cylinder. All functions are pure and thread-safe; bad input throws
// std::invalid_argument naming the parameter and the value.
#pragma once

#include "sim/core/vec.h"

namespace pelage::renderer {

// d'Eon et al. 2011: absorption per unit concentration of each pigment.
inline constexpr Rgb eumelanin_sigma_a{0.419f, 0.697f, 1.37f};
inline constexpr Rgb pheomelanin_sigma_a{0.187f, 0.4f, 1.05f};

// σ_a = eumelanin·eumelanin_sigma_a + pheomelanin·pheomelanin_sigma_a; both ≥ 0.
Rgb sigma_a_from_melanin(float eumelanin, float pheomelanin);

// Chiang et al. 2016 §4.2: σ_a whose multiply scattered look is `colour` (each channel in
// (0, 1]; 1 gives σ_a = 0) for azimuthal roughness beta_n ∈ (0, 1].
Rgb sigma_a_from_colour(Rgb colour, float beta_n);

}  // namespace pelage::renderer
