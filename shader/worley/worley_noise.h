// Cellular texture basis (S. Worley, "A Cellular Texture Basis Function", SIGGRAPH 1996):
// feature points scattered through space, a Poisson-distributed number per unit cube,
// and F1/F2 — the distances from a point to its nearest and second-nearest feature point.
// Each feature point also carries a hash, from which the baseline plugin draws a cell
// type, so a Worley pattern is a Voronoi mosaic of two colours, like the CM's.
#pragma once

#include <cstdint>

namespace pelage::shader::worley {

struct WorleyResult {
    float f1 = 0, f2 = 0;
    uint32_t id1 = 0;  // hash of the nearest feature point (stable, seed-dependent)
};

// p in feature-space units (one unit = one cube of mean density `mean_points`).
// mean_points: Poisson mean per cube (Worley uses 1 to 4; we default to 3 in the plugin).
WorleyResult worley(const float p[3], uint32_t seed, float mean_points);

// The feature points of unit cube (x, y, z): their count (at most 16) in the return
// value, positions and hashes in `points` / `ids`. worley() is the nearest-two search
// over these.
int worley_cube_points(int32_t x, int32_t y, int32_t z, uint32_t seed, float mean_points,
                       float points[16][3], uint32_t ids[16]);

}  // namespace pelage::shader::worley
