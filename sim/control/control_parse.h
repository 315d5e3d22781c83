// Reading the control blocks of a preset (control_spec.h): "regions", "masks" and the
// parameters that may be given per region. Objects are read in their listed order
// (ordered_json), since a local value applies its regions in that order. Every error is
// an InputError naming the preset file and the JSON path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/control/control_spec.h"

namespace pelage::sim {

// "regions": {name: region, ...}. Texture paths are resolved against the folder of
// `file` (the preset).
void parse_regions(const nlohmann::ordered_json &regions, const std::string &file,
                   ControlSpec *spec);

// "masks": [{"type", "only_in" | "not_in", "otherwise"}, ...], after the regions.
void parse_masks(const nlohmann::ordered_json &masks, const std::string &file,
                 const std::vector<std::string> &type_names, ControlSpec *spec);

// A number, or {"default": number, "in": {region: number, ...}}; every number must lie
// in [lo, hi] (and be > lo when `lo_open`).
struct ValueRange {
    double lo, hi;
    bool lo_open = false;
};
LocalValue parse_local_value(const nlohmann::ordered_json &v, const std::string &path,
                             const std::string &file, const ControlSpec &spec,
                             ValueRange range);

// Whether a JSON value is a local value's object form.
inline bool is_local_value(const nlohmann::ordered_json &v) { return v.is_object(); }

}  // namespace pelage::sim
