// Clumping: guide strands spread area-uniformly over the skin, one per π·r² (r the clump
// radius); every strand's points are pulled towards its nearest guide's, more towards
// the tip (weight clump·s at fraction s of the length), as hair tufts do when wet or
// matted.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "renderer/fur/fur_params.h"
#include "renderer/fur/root_sampling.h"

namespace pelage::renderer {

class ClumpGuides {
  public:
    // No guides (and no clumping) when no strand clumps (params.clump == 0 everywhere).
    ClumpGuides(const FurParams &params, const SkinMesh &mesh, const RootSampler &roots);
    size_t size() const { return m_roots.size(); }
    // Pulls line[0 .. S] (a strand rooted at line[0]) towards the nearest guide within
    // 2·radius of its root, by `clump` at the tip; the guide's shape is scaled by
    // `scale` (the strand's groomed length over the coat's). A strand with no guide that
    // near stays as it is.
    void pull(Vec3f *line, float clump, float scale) const;

  private:
    uint64_t key(Vec3f p) const;

    const FurParams &m_params;
    float m_cell = 1;
    std::vector<Vec3f> m_roots;
    std::vector<Vec3f> m_lines;  // (segments + 1) per guide
    std::unordered_map<uint64_t, std::vector<uint32_t>> m_grid;
};

}  // namespace pelage::renderer
