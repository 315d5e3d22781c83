// Ray cones: how wide a path's footprint is at each hit, for plugins that filter what
// they shade over it (PelageHit::footprint: texture MIP levels, soft cell boundaries,
// the clonal mosaic's level of detail).
//
// A camera ray starts as a cone as wide as the share of the pixel its sample stands
// for (camera_spread_scale()): its width grows by t × spread along every segment. A rough
// bounce widens the spread by the angle that one sampled direction stands for. Of the N
// directions the pixel's N samples draw from a density p (per steradian), one represents
// a solid angle of about 1 / (N p) — the argument of path differentials for sampled
// directions (Suykens & Willems 2001, "Path differentials and applications", EGWR 2001)
// and of the ray widths Christensen et al. 2003 give diffuse rays ("Ray differentials and
// multiresolution geometry caching", Eurographics 2003). A cone of solid angle Ω is about
// π (θ/2)² for a full angle θ, so θ = 2 √(Ω / π). A glossy lobe (large p) widens little,
// a diffuse one a lot. As N grows the widening vanishes: texture filtering converges to
// the point samples it replaces.
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

// The camera cone's width, in pixels, for one of `spp` samples per pixel. Each sample
// stands for 1/spp of the pixel's area, so for a square 1/√spp pixel wide: what a plugin
// filters over one sample, while the pixel filter averages the samples (pbrt-v4's
// RayIntegrator scales its camera ray differentials by the same factor). At least 1/8
// pixel: past 64 spp the filtering stays a sliver instead of vanishing. As with
// bounce_spread(), filtering converges towards point samples as spp grows, and at 1 spp a
// sample covers its whole pixel.
inline float camera_spread_scale(int spp) {
    if (spp <= 1) return 1;
    return std::max(0.125f, 1 / std::sqrt(float(spp)));
}

}  // namespace pelage::renderer
