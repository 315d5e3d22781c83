// One strand's centre line: from its root along the comb direction, bent by gravity,
// curled into a helix. A polyline of segments + 1 points, root first.
#pragma once

#include <cstdint>

#include "renderer/fur/fur_params.h"
#include "renderer/fur/root_sampling.h"
#include "renderer/fur/strand_groom.h"

namespace pelage::renderer {

inline constexpr int max_segments = 64;

// Random numbers a strand's shape draws (each in [0, 1)).
struct StrandRandom {
    float jitter_u, jitter_v;  // comb jitter: azimuth and amount
    float curl_phase;
};

// Fills out[0 .. segments] for a root at p with unit skin normal n and strand length L;
// `comb` is the comb direction at the root (FurParams::comb_direction, or the field's).
// The comb angle and curl are the strand's own (`groom`).
void grow_centre_line(const FurParams &params, const StrandGroom &groom, Vec3f p, Vec3f n,
                      Vec3f comb, float L, const StrandRandom &r, Vec3f *out);

// The comb direction at `root`: the field's there (its corners' blend) when the skin has
// one, else FurParams::comb_direction.
inline Vec3f comb_at(const FurParams &params, const SkinMesh &mesh,
                     const SurfacePoint &root) {
    if (!mesh.comb_by_corner) return params.comb_direction;
    const float *c = &mesh.comb_by_corner[9 * size_t(root.triangle)];
    const float b1 = root.b1, b2 = root.b2, b0 = 1 - b1 - b2;
    return Vec3f{c[0], c[1], c[2]} * b0 + Vec3f{c[3], c[4], c[5]} * b1 +
           Vec3f{c[6], c[7], c[8]} * b2;
}

// Unit vector ⊥ n along which a strand leaves its root before tilting up by the comb
// angle: the comb direction projected onto the tangent plane (any tangent when the comb
// is parallel to n or zero).
Vec3f comb_tangent(const FurParams &params, Vec3f n, Vec3f comb);

}  // namespace pelage::renderer
