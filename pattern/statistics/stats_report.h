// What `pelage stats` reports of a pattern, as the JSON its keys are a contract for
// (apps/pelage/cmd_stats.cpp lists them): the counts, the look measured on the surface
// through the closest-cell search (area fractions, spots) and, for cells grown with
// anisotropy, how their borders follow its field. One function for the command and for
// `pelage explore`'s statistics panel, so the two always show the same numbers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "pattern/mosaic/pattern.h"

namespace pelage::pattern::statistics {

struct StatsReportOptions {
    size_t area_samples = 200000;  // surface points of the area fractions
    double grid_resolution = 6;    // grid steps per cell spacing of the spot statistics
    uint64_t seed = 1;             // of the surface points
};

// Every key but mask_adherence (which needs the mesh file's attributes). `file` names
// the cells in messages; a recorded preset this pelage cannot read leaves out the
// stripe keys and says why in `*warning` (when given).
nlohmann::json stats_report(const mosaic::MosaicPattern &pattern, const std::string &file,
                            const StatsReportOptions &options,
                            std::string *warning = nullptr);

}  // namespace pelage::pattern::statistics
