#include "pattern/mosaic/cell_table.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace pelage::pattern::mosaic {

CellTable make_cell_table(size_t num_triangles, std::span<const CellOnSurface> cells) {
    CellTable table;
    table.row.assign(num_triangles + 1, 0);
    for (const CellOnSurface &c : cells) {
        if (c.tri >= num_triangles)
            throw std::invalid_argument("cell " + std::to_string(c.id) +
                                        " lies on triangle " + std::to_string(c.tri) +
                                        " of a mesh with " +
                                        std::to_string(num_triangles));
        ++table.row[c.tri + 1];
    }
    std::partial_sum(table.row.begin(), table.row.end(), table.row.begin());
    std::vector<uint32_t> order(cells.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return cells[a].tri != cells[b].tri ? cells[a].tri < cells[b].tri
                                            : cells[a].id < cells[b].id;
    });
    table.x.reserve(cells.size());
    table.z.reserve(cells.size());
    table.id.reserve(cells.size());
    table.type.reserve(cells.size());
    for (uint32_t k : order) {
        table.x.push_back(static_cast<float>(cells[k].x));
        table.z.push_back(static_cast<float>(cells[k].z));
        table.id.push_back(cells[k].id);
        table.type.push_back(cells[k].type);
    }
    return table;
}

}  // namespace pelage::pattern::mosaic
