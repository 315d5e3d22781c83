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

// σ_a whose coat reflects the fraction `colour` of uniform white light (its
// bihemispherical albedo: what a Lambertian skin's albedo means), where the coat is
// `depth` fibre cross-sections deep over a point of skin (fur_depth() in
// renderer/fur/strand_groom.h) and lies on a skin of albedo `skin`: what a user's
// colour means on an animal. Real coats are thin (`pelage look`'s cow has about two
// cross-sections), so much of the light a thick coat's fibres would absorb reaches the
// skin and comes back, and sigma_a_from_colour's fibres show a dark colour two to three
// times too bright there. The coat's albedo over the skin is the adding equation
// A = R + T²·s / (1 − s·R) (van de Hulst 1980; Hanrahan & Krueger 1993 §4) of its
// measured albedo R over a black skin and transmittance T² there and back
// (renderer/bsdf/fit_hair_coat.py, hair_coat_table.h, on `pelage look`'s coat at
// β_n = 0.3; other β_n scale σ_a by the thick table's ratio between β_n and 0.3),
// solved for σ_a per channel. A colour no σ_a reaches (a light colour over a dark skin
// under a thin coat, or the reverse) gets the nearest: clear fibres, or the darkest the
// table extends to.
Rgb sigma_a_from_coat_colour(Rgb colour, float beta_n, float depth, Rgb skin);

// Chiang et al. 2016 §4.2's closed form of the same inverse (what pbrt and Cycles use):
// σ_a = (ln c / (5.969 − 0.215 β_n + 2.532 β_n² − 10.73 β_n³ + 5.574 β_n⁴ + 0.245
// β_n⁵))².
Rgb sigma_a_from_colour_chiang(Rgb colour, float beta_n);

}  // namespace pelage::renderer
