// The mosaic's coarse level of detail: what a footprint wider than the mesh's triangles
// sees is the mean look of the cells under it, not one of them. Indirect hits after a
// rough bounce have such footprints (renderer/core/ray_cone.h), and so do minified
// objects. Like the coarse levels of a MIP map, the mean is precomputed: per triangle,
// the area-weighted mean look over the triangle (the nearest cell at the centres of an n
// × n sub-triangle grid, all of equal area, through the renderer's own search); per
// vertex, the area-weighted mean of its triangles'; at a hit, the three vertices' means
// interpolated by the barycentric coordinates — a filter about two triangles wide,
// continuous across edges.
//
// Footprints up to one triangle size s (its longest edge) take the exact pattern, from
// 2 s on the filtered one, linearly in between (weight()). Thread-safe after
// construction.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "pattern/mosaic/pattern.h"

namespace pelage::pattern::mosaic {

// What the material blends: colour and the fur's melanins.
struct FilteredLook {
    static constexpr int channels = 5;
    float v[channels] = {0, 0, 0, 0, 0};  // r, g, b, eumelanin, pheomelanin
};

class MosaicLod {
  public:
    // `look_of(cell)`: the look of a cell (CellTable index); `num_types`: cell types,
    // for each triangle's dominant type.
    MosaicLod(const sim::Surface &surface, const ClosestCellIndex &index,
              const std::function<FilteredLook(uint32_t cell)> &look_of,
              size_t num_types);
    MosaicLod(const MosaicPattern &pattern,
              const std::function<FilteredLook(uint32_t cell)> &look_of, size_t num_types)
        : MosaicLod(pattern.surface(), pattern.index(), look_of, num_types) {}

    // The weight of the filtered look for footprint width w at triangle t, in [0, 1].
    float weight(uint32_t t, float w) const {
        if (w <= m_smallest) return 0;  // most camera hits: no read of t's line
        const float x = w * m_tris[t].inv_size - 1;
        return !(x > 0) ? 0.0f : (x >= 1 ? 1.0f : x);  // (a NaN footprint: 0)
    }
    // Footprints up to this width get weight 0 on every triangle (the least triangle
    // size).
    float exact_up_to() const { return m_smallest; }
    // The filtered look at barycentric point (b1, b2) of t.
    FilteredLook at(uint32_t t, float b1, float b2) const;
    // The type covering most of t (for what is not blended: roughness, ior).
    uint32_t dominant_type(uint32_t t) const { return m_dominant[t]; }
    // t's own mean look (tests).
    const FilteredLook &triangle_mean(uint32_t t) const { return m_means[t]; }

  private:
    // One cache line per triangle: its corners' looks and 1 / s.
    struct alignas(64) Triangle {
        float corner[3][FilteredLook::channels];  // at vertices 0, 1, 2
        float inv_size;
    };
    static_assert(sizeof(Triangle) == 64);
    std::vector<Triangle> m_tris;
    float m_smallest = 0;  // the least triangle size: below it every weight is 0
    std::vector<FilteredLook> m_means;
    std::vector<uint32_t> m_dominant;
};

}  // namespace pelage::pattern::mosaic
