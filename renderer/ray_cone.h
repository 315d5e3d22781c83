// Ray cones: how wide a path's footprint is at each hit, for plugins that filter what
// they shade over it (PelageHit::footprint: texture MIP levels, soft cell boundaries,
// the clonal mosaic's level of detail).
//
// A camera ray starts as a cone one pixel wide: its width grows by t × spread along
// every segment. A rough bounce widens the spread by the angle that one sampled
// direction stands for. Of the N directions the pixel's N samples draw from a density
// p (per steradian), one represents a solid angle of about 1 / (N p) — the argument of
// path differentials for sampled directions (Suykens & Willems 2001, "Path
// differentials and applications", EGWR 2001) and of the ray widths Christensen et al. 2003
// give diffuse rays ("Ray differentials and multiresolution geometry caching", Eurographics
// 2003).
// A cone of solid angle Ω is about π (θ/2)² for a full angle θ, so θ = 2 √(Ω / π).
// A glossy lobe (large p) widens little, a diffuse one a lot. As N grows the widening
// vanishes: texture filtering converges to the point samples it replaces.
#pragma once

#include <algorithm>
#include <cmath>

namespace pelage::renderer {

// The spread (full cone angle, radians) a non-specular bounce adds, for a direction
// drawn with solid-angle density `pdf`, one of `spp` per pixel. At most π (a hemisphere).
inline float bounce_spread(float pdf, int spp) {
    constexpr float pi = 3.14159265358979f;
    if (!(pdf > 0) || spp < 1) return pi;
    return std::min(pi, 2 * std::sqrt(1 / (pi * float(spp) * pdf)));
}

}  // namespace pelage::renderer
