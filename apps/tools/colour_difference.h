// CIE 1976 L*a*b* of a linear sRGB reflectance and the CIE 1976 colour difference ΔE*ab
// between two of them, the distance `pelage bench preset-colour` reports between a
// preset's colour and the colour a render shows.
#pragma once

#include <array>

#include "sim/core/vec.h"

namespace pelage::renderer {

// L*a*b* (CIE 15:2004 §8.2.1) of linear sRGB `rgb` (IEC 61966-2-1 primaries, D65), with
// white the XYZ of RGB (1, 1, 1): a perfect white reflector is L* 100, a* = b* = 0.
std::array<double, 3> cie_lab(const Rgb &rgb);

// ΔE*ab (CIE 1976): the Euclidean distance in L*a*b*. About 2.3 is a just noticeable
// difference (Sharma, Digital Color Imaging Handbook, 2003, §1.7).
double delta_e76(const Rgb &a, const Rgb &b);

}  // namespace pelage::renderer
