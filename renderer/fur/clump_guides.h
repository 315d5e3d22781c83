// Clumping: guide strands spread area-uniformly over the skin, one per π·r² (r the clump
// radius); every strand's points are pulled towards its nearest guide's, more towards
// the tip (weight clump·s at fraction s of the length), as hair tufts do when wet or
// matted.
#pragma once

#include <cstdint>
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
    // The guide pull() takes for a root at p: the nearest within 2·radius, the lowest
    // index among equally near ones; -1 when none is that near.
    int64_t nearest(Vec3f p) const;
    Vec3f root(size_t guide) const { return m_roots[guide]; }

  private:
    uint64_t key(Vec3f p) const;
    // The guides in the grid cell of `key`: [*begin, *end) into m_members.
    bool cell(uint64_t key, uint32_t *begin, uint32_t *end) const;

    const FurParams &m_params;
    float m_cell = 1;
    std::vector<Vec3f> m_roots;
    std::vector<Vec3f> m_lines;  // (segments + 1) per guide
    // The guides by grid cell, as a flat open-addressed table (linear probing, a power
    // of two slots, at most half full): every strand probes 27 cells, and a node-based
    // map there cost more than growing the strand.
    std::vector<uint32_t> m_members;     // guide indices, grouped by cell
    std::vector<uint64_t> m_slot_key;    // a cell's key + 1 (0: empty slot)
    std::vector<uint32_t> m_slot_begin;  // its first member; it ends where ...
    std::vector<uint32_t> m_slot_end;    // ... this says
};

}  // namespace pelage::renderer
