// A debugging view of a .cells file (not the renderer): the mesh flat-shaded in an
// orthographic projection, with every cell drawn as a dot of its type's colour.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/cells_io/cells_file.h"

namespace pelage::sim {

struct PreviewImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  // 8-bit sRGB, row-major, top row first
};

struct PreviewOptions {
    int size = 800;  // longer side in pixels, the other side following the mesh
    // Both > 0: exactly this image instead, the mesh fit inside it and centred.
    int width = 0, height = 0;
    std::array<double, 3> view{0, 0, -1};  // viewing direction (world)
    int dot_radius = 1;                    // pixels
};

PreviewImage render_cells_preview(const CellsData &data, const PreviewOptions &options);

}  // namespace pelage::sim
