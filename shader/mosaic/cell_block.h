// What the closest-cell index stores (closest_cell.h): candidate cells already carried
// into a triangle's frame, five to a 64-byte block, and the one distance expression every
// search uses.
#pragma once

#include <cstdint>

namespace pelage::shader::mosaic {

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

}  // namespace pelage::shader::mosaic
