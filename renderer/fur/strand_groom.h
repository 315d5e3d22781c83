// One strand's groom: the fur's values where its root grows, by the root's cell type
// and the body regions there (FurParams::varying). Regions are resolved once per skin
// (renderer/geometry/fur_geometry.cpp, through sim/control as the presets' are) into
// weights at every triangle corner; a root's weight is their barycentric blend, so a
// groom's regions fade over the same `blend` distances as a preset's.
#pragma once

#include "renderer/fur/fur_params.h"
#include "renderer/fur/root_sampling.h"

namespace pelage::renderer {

struct StrandGroom {
    float length, density, root_radius, tip_radius;
    float beta_m, beta_n, comb_angle_deg, curl_radius, curl_turns, clump;
};

// The coat's own values (no type, no region): what clump guides grow with.
StrandGroom coat_groom(const FurParams &params);

// The groom at a root of cell type `type` (−1: unknown) whose region weights are
// `weights` (SkinMesh::num_regions of them; null when the fur has no regions).
StrandGroom strand_groom(const FurParams &params, const float *weights, int type);

// The coat's depth at a root: the mean number of fibre cross-sections over a point of
// skin, density × length × (root_radius + tip_radius) × cos(comb angle) (the shadow
// its strands cast straight down, radii linear along each), what a hair colour is
// matched in (sigma_a_from_coat_colour, renderer/bsdf/hair_pigments.h).
float fur_depth(const StrandGroom &g);

// The weight of each region at `root` (mesh.num_regions values into `out`).
void region_weights(const SkinMesh &mesh, const SurfacePoint &root, float *out);

// The highest density any root can have: the candidates' density before thinning.
double max_density(const FurParams &params);

// Whether β_m or β_n differ between strands (then each strand keeps its own).
inline bool beta_varies(const FurParams &params) {
    return params.vary(FurParams::Groomed::beta_m).varies() ||
           params.vary(FurParams::Groomed::beta_n).varies();
}

}  // namespace pelage::renderer
