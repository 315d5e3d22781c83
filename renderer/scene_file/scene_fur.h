// The `"fur": {…}` block of a scene object (docs/guide/fur.md): parsed and fully
// validated into renderer/fur's FurParams. Unknown keys and values out of range are
// pelage::InputError naming the scene file and the JSON path (objects[i].fur.length).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "renderer/fur/fur_params.h"

namespace pelage::renderer {

// `field` is the block's JSON path ("objects[0].fur"), `scene_path` the file.
FurParams read_fur(const nlohmann::ordered_json &j, const std::string &field,
                   const std::string &scene_path);

}  // namespace pelage::renderer
