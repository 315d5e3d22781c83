// Area-uniform random points on a triangle mesh (Turk 1990, "Generating random points in
// triangles", Graphics Gems I; Walter 1998 §6.4 uses it for the initial cells).
#pragma once

#include <cstdint>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::sim {

struct SurfacePointSample {
    TriId tri;
    Vec2d p;  // local CRPS coordinates on tri
};

// n points, deterministic for a given seed: the triangle is chosen with probability
// proportional to its area, then (s, t) -> barycentric (1 - sqrt(s), sqrt(s)(1 - t),
// sqrt(s) t), which is uniform on the triangle.
std::vector<SurfacePointSample> sample_surface_uniform(const Crps &crps, size_t n,
                                                       uint64_t seed);

}  // namespace pelage::sim
