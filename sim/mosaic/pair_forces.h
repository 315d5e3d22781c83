// The Clonal Mosaic's pair forces on the cells of one triangle from every cell of its
// unfolding, eight neighbours at a time (Walter 1998 Fig. 1 step 1):
//   D += (C − P)·(1 − α[C][P])·(r/d − 1)     for every P with 0 < d = |C − P| < r,
// which is unit(C − P)·(1 − d/r)·(1 − α)·r written with one square root and one division.
//
// The candidates are the cells of the triangles of the unfolding (Teo §5.1.2), in chunks
// of eight with a bounding circle each. The circles are carried into the pushed
// triangle's frame once per step; a pushed cell tests eight circles at a time, and only
// the chunks it reaches have their cells carried into its frame and met.
//
// Floats, eight lanes: lane l sums candidates l, l + 8, ..., and the lanes are added in
// one fixed tree. Only IEEE-exact operations are used (no fused multiply-add, no
// reciprocal estimate), so the AVX2 path and the scalar path give the same bits on
// every CPU, and the cells do not depend on the machine or the number of threads.
#pragma once

#include <cstdint>

namespace pelage::sim {

inline constexpr uint32_t force_lanes = 8;

// Where padding cells and chunks lie: squared distances stay finite in floats. A padding
// cell lies at (force_padding_position, 0), which any rigid map carries 1e18 away.
inline constexpr float force_padding_position = 1e18f;

// The cells lie in their own triangles' frames, each triangle's padded to whole chunks
// with padding cells. The candidate chunks are listed with the map
// into the pushed triangle's frame, padded to whole lanes of chunks with circles at
// force_padding_position.
struct ForceCandidates {
    const float *x = nullptr, *z = nullptr;
    const int32_t *type = nullptr;  // cell types, < max_cell_types
    // Per candidate chunk: where its cells start in x/z/type, the rigid map (cos, sin,
    // shift) into the pushed frame, and a circle there holding them (a margin included).
    const uint32_t *first = nullptr;
    const float *map_c = nullptr, *map_s = nullptr, *map_x = nullptr, *map_z = nullptr;
    const float *centre_x = nullptr, *centre_z = nullptr, *radius = nullptr;
    uint32_t chunks = 0;  // a multiple of force_lanes
};

// The pushed cells, in their triangle's frame.
struct ForceTargets {
    const float *x = nullptr, *z = nullptr;
    const float *r = nullptr;                // each cell's radius
    const float *one_minus_alpha = nullptr;  // 8 per cell: 1 − α felt from each type
    uint32_t count = 0;
    uint32_t self =
        0;  // cell self + k of x/z/type is target k itself (never its own push)
};

// What the kernel writes per target.
struct ForceSums {
    float *x = nullptr, *z = nullptr;  // the sum over the candidates
    // Whether a candidate lies exactly on the target (d = 0 in floats): that pair has no
    // direction, and the caller adds its tie-break push.
    uint8_t *coincident = nullptr;
    uint32_t *pairs = nullptr;  // candidates within r (the work that is not wasted)
};

void add_pair_forces(const ForceTargets &targets, const ForceCandidates &candidates,
                     const ForceSums &out);

// The same sums in plain C++, lane by lane (what add_pair_forces runs without AVX2).
void add_pair_forces_scalar(const ForceTargets &targets,
                            const ForceCandidates &candidates, const ForceSums &out);

// Whether add_pair_forces runs eight lanes in AVX2 on this CPU.
bool pair_forces_use_avx2();

// Whether target (x, z) with radius r can reach chunk c: the test both paths make.
inline bool reaches_chunk(float x, float z, float r, const ForceCandidates &candidates,
                          uint32_t c) {
    const float dx = x - candidates.centre_x[c], dz = z - candidates.centre_z[c];
    const float reach = r + candidates.radius[c];
    return dx * dx + dz * dz <= reach * reach;
}

}  // namespace pelage::sim
