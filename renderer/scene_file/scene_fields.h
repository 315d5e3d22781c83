// Every field of a scene file, declared once. The parsers (scene_file.cpp, and
// scene_fur.cpp for an object's fur) read only declared fields, through DeclaredFields,
// and name an unknown one with the closest declared spelling; the files a render depends
// on are those its `input` fields name (what `--resume` and the settings hash trust,
// renderer/job/input_hash.h); and the reference tables of docs/guide/scene-format.md
// and docs/guide/fur.md are written from the same rows (`pelage fields`, make_tables.py;
// a test fails when a page differs). Adding a field is one row here and its reading in
// the parser. Values that are objects of their own (a material's plugin parameters, a
// groom's regions, a comb field) are checked by their own readers.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/core/json_fields.h"

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
    // The reference table that shows it (empty: described in prose) and its name there
    // (empty: shown by the row before, as "`width`, `height`").
    std::string_view table{}, shown{};
    // The row's other cells, in the table's columns' order (type, default, meaning; the
    // fur's default, range, meaning).
    std::array<std::string_view, 3> cells{};
};

std::span<const SceneField> scene_fields();
// The field `key` of `block`, or null when the scene format has none.
const SceneField *scene_field(std::string_view block, std::string_view key);
// The keys of `block`, in declaration order.
std::vector<std::string> scene_field_keys(std::string_view block);
// The block of an object at JSON path `json_path`: "objects[2].material" →
// "objects.material".
std::string scene_block_of(std::string_view json_path);
// The reference tables ("camera", "film", ..., "fur"), the page that holds one (from the
// repository's root), and one as Markdown.
std::vector<std::string> scene_field_tables();
std::string scene_field_page(std::string_view table);
std::string scene_fields_markdown(std::string_view table);

// One object of a scene file read field by field (sim/core/json_fields.h), knowing its
// block from its JSON path: reading an undeclared field is a programming error
// (std::logic_error), and an unknown key is named with the closest declared one.
class DeclaredFields : public sim::JsonObjectFields {
  public:
    DeclaredFields(const json &j, std::string path, std::string file);
    DeclaredFields(json &&, std::string, std::string) = delete;
    // How the field `key` of this object is used (FieldUse::value when undeclared).
    FieldUse use(const std::string &key) const;

  protected:
    void asked(const std::string &key) const override;
    std::vector<std::string> known_keys() const override;

  private:
    std::string m_block;
};

}  // namespace pelage::renderer
