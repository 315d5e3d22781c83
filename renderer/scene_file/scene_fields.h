// Every field of a scene file, declared once. The parser (scene_file.cpp) reads only
// declared fields and names an unknown one with the closest declared spelling; the files
// a render depends on are those its `input` fields name (what `--resume` and the
// settings hash trust, renderer/job/input_hash.h); and the reference tables of
// docs/guide/scene-format.md are written from the same rows (`pelage fields`; a test
// fails when the page differs). Adding a field is one row here and its reading in
// scene_file.cpp.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pelage::renderer {

enum class FieldUse {
    value,   // a value in the scene text itself
    input,   // a file (or FILE#OBJECT) the render reads: hashed for --resume
    output,  // a file the render writes
};

struct SceneField {
    // The object that holds the field, as a JSON path without array indices:
    // "objects.material", "film.filter"; "" for the top level.
    std::string_view block;
    std::string_view key;  // as pelage spells it ("colour"; "color" is accepted too)
    FieldUse use = FieldUse::value;
    // The reference table that shows it (empty: described in prose), its name there
    // (empty: shown by the row before, as "`width`, `height`"), and the table's cells.
    std::string_view table, shown, type, fallback, meaning;
};

std::span<const SceneField> scene_fields();
// The field `key` of `block`, or null when the scene format has none.
const SceneField *scene_field(std::string_view block, std::string_view key);
// The keys of `block`, in declaration order.
std::vector<std::string> scene_field_keys(std::string_view block);
// The block of an object at JSON path `json_path`: "objects[2].material" →
// "objects.material".
std::string scene_block_of(std::string_view json_path);
// The reference tables ("camera", "film", ...) and one of them as Markdown.
std::vector<std::string> scene_field_tables();
std::string scene_fields_markdown(std::string_view table);

}  // namespace pelage::renderer
