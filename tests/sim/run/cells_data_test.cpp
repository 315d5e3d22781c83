// A run's side of the .cells format (sim/run/cells_data.h): the type table as the file
// keeps it, and the preset's anisotropy field recorded so that sim/field alone reads
// back the field the run used.
#include "sim/run/cells_data.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "sim/field/field_spec.h"
#include "sim/mosaic/preset.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// The two-type preset with `anisotropy` in its simulation block ("" for none).
sim::Preset preset_with(const TempDir &tmp, const std::string &anisotropy) {
    std::string text = slurp(two_type_preset(tmp, 50));
    if (!anisotropy.empty())
        text.replace(text.find(R"("relax": "global")"), 17,
                     R"("relax": "global", "w_a": 0.5, "anisotropy": )" + anisotropy);
    return sim::parse_preset(text, "preset.json");
}

// Bit for bit (FieldControl has no ==).
bool same(const sim::FieldSpec &a, const sim::FieldSpec &b) {
    if (a.kind != b.kind || a.direction != b.direction ||
        a.controls.size() != b.controls.size() || a.box_space != b.box_space ||
        a.heat != b.heat || a.diffusion_time != b.diffusion_time)
        return false;
    for (size_t i = 0; i < a.controls.size(); ++i)
        if (a.controls[i].at != b.controls[i].at ||
            a.controls[i].direction != b.controls[i].direction)
            return false;
    return true;
}

TEST(CellsData, TheTypeTableKeepsWhatTheFileStores) {
    TempDir tmp;
    const sim::Preset p = preset_with(tmp, "");
    const std::vector<sim::CellsFileType> types = sim::cells_file_types(p.types);
    ASSERT_EQ(types.size(), 2u);
    for (int i = 0; i < 2; ++i) {
        const sim::CellType &t = p.types[i];
        EXPECT_EQ(types[i].name, t.name);
        EXPECT_EQ(types[i].colour, t.colour);
        EXPECT_EQ(types[i].eumelanin, t.eumelanin);
        EXPECT_EQ(types[i].pheomelanin, t.pheomelanin);
        EXPECT_EQ(types[i].division_time, t.division_time);
        EXPECT_EQ(types[i].initial_probability, t.initial_probability);
    }
}

TEST(CellsData, TheRecordedFieldParsesToTheFieldTheRunUsed) {
    TempDir tmp;
    for (const char *field :
         {R"({"around": "body_axis"})", R"({"direction": [1, 2, 0.3]})",
          R"({"controls": [{"at": [0.5, 0.5, 0.5], "direction": [0, 3, 1]}],
              "space": "box", "interpolation": "heat", "diffusion_time": 2})"}) {
        const sim::Preset p = preset_with(
            tmp, std::string(R"({"field": )") + field + R"(, "magnitude": 1})");
        const nlohmann::json node =
            sim::recorded_anisotropy_field(nlohmann::json::parse(p.json_text));
        ASSERT_TRUE(node.is_object()) << field;
        // Bit for bit: the same text through the same parser.
        EXPECT_TRUE(same(sim::parse_field_spec(node, "anisotropy_field", "a.cells"),
                         p.params.anisotropy_field))
            << field;
    }
    // A one-direction anisotropy, or none: no field, recorded as null.
    for (const char *anisotropy : {R"({"direction": [0, 1, 0], "magnitude": 1})", ""}) {
        const sim::Preset p = preset_with(tmp, anisotropy);
        EXPECT_EQ(p.params.anisotropy_field.kind, sim::FieldSpec::Kind::none);
        EXPECT_TRUE(
            sim::recorded_anisotropy_field(nlohmann::json::parse(p.json_text)).is_null())
            << anisotropy;
    }
}

}  // namespace
}  // namespace pelage::test
