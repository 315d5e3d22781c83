// A run's cells packed as a .cells file holds them (sim/cells_io/cells_file.h): the
// simulation's side of the format, which reads none of the mosaic model.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/crps.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"

namespace pelage::sim {

// What the file stores of a cell type, and of every type in order.
CellsFileType cells_file_type(const CellType &type);
std::vector<CellsFileType> cells_file_types(const CellTypes &types);

CellsData make_cells_data(const TriangleMesh &mesh, const Crps &crps,
                          const CellTypes &types, const Cells &cells,
                          const std::string &params_json, uint64_t seed);

// The params' "anisotropy_field": the preset's simulation.anisotropy.field as the preset
// (JSON, as read) gives it, which parse_field_spec (sim/field/field_spec.h) turned into
// the field the run used, so the fur's `"comb": "field"` resolves the same field from
// the file; null when the preset has none.
nlohmann::json recorded_anisotropy_field(const nlohmann::json &preset);

}  // namespace pelage::sim
