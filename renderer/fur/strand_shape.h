// One strand's centre line: from its root along the comb direction, bent by gravity,
// curled into a helix. A polyline of segments + 1 points, root first.
#pragma once

#include <cstdint>

#include "renderer/fur/fur_params.h"

namespace pelage::renderer {

inline constexpr int max_segments = 64;

// Random numbers a strand's shape draws (each in [0, 1)).
struct StrandRandom {
    float jitter_u, jitter_v;  // comb jitter: azimuth and amount
    float curl_phase;
};

// Fills out[0 .. segments] for a root at p with unit skin normal n and strand length L.
void grow_centre_line(const FurParams &params, Vec3f p, Vec3f n, float L,
                      const StrandRandom &r, Vec3f *out);

// Unit vector ⊥ n along which a strand leaves its root before tilting up by the comb
// angle: the comb direction projected onto the tangent plane (any tangent when the comb
// is parallel to n).
Vec3f comb_tangent(const FurParams &params, Vec3f n);

}  // namespace pelage::renderer
