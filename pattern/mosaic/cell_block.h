// What the closest-cell index stores (closest_cell.h): candidate cells already carried
// into a triangle's frame, five to a 64-byte block, the triangle's frame, the windows of
// bent entries, and the one distance expression every search uses. The index's build
// writes them, its searches and the coherent path (coherent_lookup.h) read them.
#pragma once

#include <cstdint>

namespace pelage::pattern::mosaic {

struct Vec2f {
    float x = 0, y = 0;
};

// |q - (x, y)|², the one expression every search and reuse uses (the scans,
// lane_scan.h, coherent_lookup.h), so that their results are the same bits.
inline float squared_distance(float x, float y, Vec2f q) {
    const float dx = x - q.x, dy = y - q.y;
    return dx * dx + dy * dy;
}

// Five candidate cells in a triangle's frame; padding entries have cell == none (all bits
// set) and x = y = +inf. Five (60 bytes and the bound) rather than four: the line has
// room for them. Lists are runs of blocks sorted by bound2.
struct alignas(64) CellBlock {
    static constexpr int size = 5;
    float x[size], y[size];
    uint32_t cell[size];
    float bound2;  // squared lower bound of the distance from the region, for all five
};
static_assert(sizeof(CellBlock) == 64);

// A triangle in its frame, q = v0 + b1 e1 + b2 e2, and 1 / det(e1, e2) for the
// barycentric coordinates of a point (a search from a point q).
struct alignas(32) TriangleFrame {
    float v0x, v0y, e1x, e1y, e2x, e2y, inv_det;
    // Local CRPS coordinates of barycentric point (b1, b2).
    Vec2f point(float b1, float b2) const {
        return {v0x + b1 * e1x + b2 * e2x, v0y + b1 * e1y + b2 * e2y};
    }
};
static_assert(sizeof(TriangleFrame) == 32);

// A list entry whose cell's distance over the region is not one straight line
// from one position — its path bends round a pseudo-source vertex (σ > 0), or
// different parts of the region see the cell through different unfoldings — is
// listed at the position of the unfolding that serves most of the region (the source
// moved back by σ for a bent path) and carries this flag with the index of its
// first window in the bent table: the cell's windows on the triangle, from which the
// returned cells' exact distances come (the least σ + |q - s| over the windows
// whose wedge holds q). A run of windows starts with one tagged with its cell and
// goes on while the tag says `more`: one cache line holds the cell and two windows,
// so a bent result costs one more miss, not two.
inline constexpr uint32_t bent_flag = 0x80000000u;
struct alignas(32) BentWindow {
    static constexpr uint32_t more = 0xffffffffu;
    float sx, sy, sigma;
    float x0x, x0y, x1x, x1y;       // the wedge's entry interval; whole face: x0x = NaN
    uint32_t tag;                   // the cell on a run's first window, else `more`
    float distance(Vec2f q) const;  // +inf when q lies outside the wedge
    bool covers(Vec2f q) const;
};
static_assert(sizeof(BentWindow) == 32);

}  // namespace pelage::pattern::mosaic
