// pelage spells "colour" (docs/guide/scene-format.md); scene files, presets and shader
// parameters accept "color" as well, in every key that holds the word ("colour",
// "spot_colour"). One object giving both spellings of a key is an error naming it.
#pragma once

#include <string>

#include "sim/core/input_error.h"

namespace pelage {

// `key` in the other spelling: "colour" as "color" ("spot_colour" -> "spot_color") and
// "color" as "colour"; "" when `key` holds neither word.
inline std::string other_colour_spelling(const std::string &key) {
    if (const size_t at = key.find("colour"); at != std::string::npos)
        return key.substr(0, at) + "color" + key.substr(at + 6);
    if (const size_t at = key.find("color"); at != std::string::npos)
        return key.substr(0, at) + "colour" + key.substr(at + 5);
    return "";
}

// The spelling of `key` that `object` holds: `key`, its other spelling, or `key` when it
// holds neither. Both: InputError(file, 0, field_path). `object` is anything with
// contains(std::string), such as nlohmann::json.
template <typename Object>
std::string spelling_in(const Object &object, const std::string &key,
                        const std::string &file, const std::string &field_path) {
    const std::string other = other_colour_spelling(key);
    if (other.empty() || !object.contains(other)) return key;
    if (object.contains(key))
        throw InputError(
            file, 0, field_path,
            "given twice, as \"" + key + "\" and as \"" + other + "\": keep one");
    return other;
}

}  // namespace pelage
