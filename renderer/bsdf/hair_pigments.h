// Absorption coefficients σ_a for the hair BSDF (hair_bsdf.h), from pigment or from
// colour.
//
//  * Melanin: σ_a = c_eu·σ_eu + c_pheo·σ_pheo with the eumelanin and pheomelanin
//  absorption
//    spectra of d'Eon, Francois, Hill, Letteri, Aubry 2011, "An Energy-Conserving Hair
//    Reflectance Model", Computer Graphics Forum 30(4):1181–1187,
//    doi:10.1111/j.1467-8659.2011.01976.x (RGB values as used by pbrt-v3/v4 and Cycles).
//    Concentrations are dimensionless (0 = no pigment; about 8 is black hair).
//  * Colour: the σ_a whose fibres, in a thick coat, show the colour after multiple
//    scattering: the albedo of a semi-infinite slab of such fibres under uniform white
//    light. Chiang, Bitterli, Tappan, Burley 2016 (doi:10.1111/cgf.12830) §4.2 fit a
//    closed form, ln c = −D(β_n)·sqrt(σ_a), to their renders; pelage's own slab (its
//    BSDF, its fur) reflects up to 3× less than that form asks for dark colours, so
//    sigma_a_from_colour inverts a table of pelage's slab measured the same way
//    (renderer/bsdf/fit_hair_colour.py, hair_colour_table.h).
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

// σ_a whose thick slab of fibres reflects `colour` (each channel in (0, 1]; 1 gives
// σ_a = 0) for azimuthal roughness beta_n ∈ (0, 1]: the measured table, linear in β_n
// and in sqrt(σ_a) between its entries, extended linearly past its darkest entry.
Rgb sigma_a_from_colour(Rgb colour, float beta_n);

// Chiang et al. 2016 §4.2's closed form of the same inverse (what pbrt and Cycles use):
// σ_a = (ln c / (5.969 − 0.215 β_n + 2.532 β_n² − 10.73 β_n³ + 5.574 β_n⁴ + 0.245
// β_n⁵))².
Rgb sigma_a_from_colour_chiang(Rgb colour, float beta_n);

}  // namespace pelage::renderer
