// Presets: the cell types, parameters, spatial control and growth that configure a
// simulation, read from JSON strictly (unknown keys and out-of-range values are
// InputError naming the JSON path), and found by name among the shipped presets.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/control/control_spec.h"
#include "sim/growth/growth_spec.h"
#include "sim/mosaic/cell_types.h"

namespace pelage::sim {

struct Preset {
    std::string name, description;
    std::string animal;   // the animal it is drawn from ("snow leopard (Panthera uncia)")
    std::string extends;  // the base preset's name when it extends one, else ""
    CellTypes types;
    SimParams params;
    // Regions, masks and local parameters (Queiroz & Walter §V); SimParams and the types
    // hold the defaults of the local ones.
    ControlSpec control;
    std::string json_text;  // the preset as read (compact JSON), stored in .cells files
    std::optional<GrowthSpec> growth;  // the "growth" block (sim/growth/growth_spec.h)
};

// Parses a preset from JSON text; `file` names the source in InputError messages, which
// carry the JSON path of the offending field (e.g. "types[1].colour"). A preset with
// "extends": "NAME" is NAME.json of `file`'s folder (else of `presets_dir`) with this
// one's name, animal, description, source, notes, "colours" and "melanins" by type name
// (docs/guide/presets.md#extending-a-preset).
Preset parse_preset(const std::string &json_text, const std::string &file,
                    const std::string &presets_dir = "");
// Reads and parses a preset file; InputError when missing or malformed.
Preset load_preset_file(const std::string &path, const std::string &presets_dir = "");

// A preset by name ("giraffe-reticulata" → presets_dir/giraffe-reticulata.json) or by
// path (anything ending in .json or containing '/'). An unknown name is an InputError at
// `field` of `file` ("--preset" on the command line; "objects[0].pattern.preset" of a
// scene) naming the closest shipped preset and listing them all.
Preset load_preset(const std::string &name_or_path, const std::string &presets_dir,
                   const std::string &file = "", const std::string &field = "--preset");
// The shipped presets' names (presets_dir/NAME.json), sorted.
std::vector<std::string> preset_names(const std::string &presets_dir);

}  // namespace pelage::sim
