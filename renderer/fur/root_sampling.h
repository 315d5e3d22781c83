// Area-uniform points on a triangle mesh: candidate i picks its triangle from the area
// CDF and its barycentrics by the square-root warp, both from hashes of (seed, i), so
// the set of roots is the same at any thread count and a prefix of a larger set.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/fur/fur_params.h"

namespace pelage::renderer {

// A triangle mesh in world space. corner_normals (9 floats per triangle) may be null:
// face normals are used then.
struct SkinMesh {
    const float *positions = nullptr;  // xyz per vertex
    // The same vertices at rest, when the skin is posed (a clip, a deformation): roots
    // are then drawn by the rest areas, so a strand keeps its (triangle, barycentric)
    // place, and the number of strands, in every pose. Null: drawn on `positions`.
    const float *rest_positions = nullptr;
    const uint32_t *triangles = nullptr;
    const float *corner_normals = nullptr;
    // FurParams::Comb::field: the comb direction at each triangle corner (xyz, world; 9
    // floats per triangle), zero where the field is undefined; null otherwise.
    const float *comb_by_corner = nullptr;
    // The fur's regions (FurParams::regions) at every triangle corner: num_regions
    // weights in [0, 1] per corner, 3 corners per triangle; null without regions.
    const float *region_corners = nullptr;
    uint32_t num_regions = 0;
    uint32_t num_vertices = 0, num_triangles = 0;
};

struct SurfacePoint {
    uint32_t triangle;
    float b1, b2;  // barycentrics of corners 1 and 2
};

class RootSampler {
  public:
    explicit RootSampler(const SkinMesh &mesh);
    double area() const { return m_cdf.empty() ? 0.0 : m_cdf.back(); }
    // Candidate i of the stream `seed`.
    SurfacePoint sample(uint64_t seed, uint64_t i) const;
    // Position and unit normal (interpolated corner normals, or the face's).
    void point_normal(const SurfacePoint &s, Vec3f *p, Vec3f *n) const;

  private:
    const SkinMesh m_mesh;
    std::vector<double> m_cdf;  // cumulative triangle areas
};

// How many candidates a mean of `expected` gives: floor, plus one with probability of
// the fraction (a hash of the seed), so the count's mean is exact.
uint64_t candidate_count(double expected, uint64_t seed);

}  // namespace pelage::renderer
