// How well a grown pattern keeps to its neural-crest masks (Queiroz & Walter §V.A;
// sim/control): for each mask, the share of the masked-out surface (where the mask is
// 0) that shows the masked type, as the renderer shows it: n area-uniform surface
// points, each taking the type of its closest cell (as area_fractions.h). Cells never
// stand where their mask is 0, but a cell near the edge of a mask covers part of it with
// its Voronoi region.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pattern/mosaic/pattern.h"
#include "sim/mosaic/preset.h"

namespace pelage::pattern::statistics {

struct MaskAdherence {
    std::string type, region, otherwise;
    bool only_in = true;
    double masked_out_share = 0;  // of the surface, where the mask is 0
    double violation = 0;  // of that masked-out area, the share showing the masked type
    size_t masked_out_samples = 0;
};

// One entry per mask of `preset` (resolved on the pattern's simulation surface; the
// pattern's mesh file `mesh_path` supplies attributes and UVs).
std::vector<MaskAdherence> measure_mask_adherence(const mosaic::MosaicPattern &pattern,
                                                  const std::string &mesh_path,
                                                  const sim::Preset &preset,
                                                  const std::string &preset_file,
                                                  size_t samples, uint64_t seed);

}  // namespace pelage::pattern::statistics
