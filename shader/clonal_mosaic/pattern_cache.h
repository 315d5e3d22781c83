// The plugin's patterns by what makes them. An animation creates an instance per frame
// (a clip, a deformation, a turntable that turns its object), all of one .cells file on
// one rest mesh: the file is read, its surface and CRPS built and its closest-cell index
// made once, and every frame's instance shares them. Only what the instance's parameters
// decide (the looks of the cells, the level of detail) is its own.
#pragma once

#include <memory>
#include <string>

#include "pattern/mosaic/pattern.h"

namespace pelage::shader::clonal_mosaic {

// The pattern of `cells_path` on the rest mesh `rest` (named `mesh_name` in messages):
// the one an instance alive or one of the last few made holds when the file (path,
// size, modification time), the mesh (its content hash) and the neighbourhood are the
// same, else a new one. Thread-safe.
std::shared_ptr<const pattern::mosaic::MosaicPattern> cached_pattern(
    const std::string &cells_path, sim::TriangleMesh rest, const std::string &mesh_name,
    pattern::mosaic::Neighbourhood neighbourhood);

}  // namespace pelage::shader::clonal_mosaic
