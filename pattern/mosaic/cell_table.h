// The cells of a simulated mosaic laid out for lookups: grouped by triangle (CSR), with
// positions in each triangle's local CRPS coordinates as float (they are the size of a
// triangle, so float keeps ~1e-7 of a triangle's size). Stable id and type sit in their
// own arrays: the search loop touches only x and z.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::pattern::mosaic {

struct CellOnSurface {
    sim::TriId tri;
    double x, z;  // local CRPS coordinates on `tri` (sim/crps/crps.h)
    uint32_t
        id;  // stable: survives re-simulation with the same seed, keys per-cell jitter
    uint8_t type;
};

struct CellTable {
    std::vector<uint32_t> row;  // cells of triangle t: [row[t], row[t + 1])
    std::vector<float> x, z;
    std::vector<uint32_t> id;
    std::vector<uint8_t> type;

    size_t size() const { return x.size(); }
    size_t num_triangles() const { return row.empty() ? 0 : row.size() - 1; }
};

// Groups cells by triangle, in (triangle, id) order so the layout is deterministic.
// Throws std::invalid_argument for a cell on a triangle >= num_triangles.
CellTable make_cell_table(size_t num_triangles, std::span<const CellOnSurface> cells);

}  // namespace pelage::pattern::mosaic
