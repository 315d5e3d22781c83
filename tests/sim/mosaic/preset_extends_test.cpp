// A preset that "extends" another takes the base's cells, regions and dynamics with its
// own name, words and colours; anything else it gives, an unknown type, a missing or
// chained base, is an InputError naming the file and the JSON path. And every shipped
// preset that extends another keeps its base's cells and changes its colours.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/core/input_error.h"
#include "sim/mosaic/preset.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

constexpr const char *base_json = R"({"name": "base", "animal": "a cat",
    "description": "spots", "source": "a table", "notes": "base notes",
    "types": [
      {"name": "F", "colour": [0.02, 0.015, 0.01], "eumelanin": 1, "pheomelanin": 0.05,
       "division_time": 8, "initial_probability": 0.2},
      {"name": "B", "colour": [0.62, 0.36, 0.11], "eumelanin": 0.05, "pheomelanin": 0.7,
       "division_time": 60, "initial_probability": 0.8}],
    "adhesion": [[0.8, 0.0], [0.0, 0.2]],
    "simulation": {"initial_cells": 100, "w_r": 2, "w_d": 0.066, "rho": 18, "end_time": 15},
    "published": {"cells_by_type": {"F": 1177, "B": 1420}}})";

std::string what(const std::string &path) {
    try {
        load_preset_file(path);
    } catch (const InputError &e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted: " << path;
    return "";
}

TEST(PresetExtends, TakesTheBaseCellsWithItsOwnWordsAndColours) {
    test::TempDir tmp;
    tmp.write("base.json", base_json);
    const std::string child = tmp.write("pale.json", R"({"name": "pale",
        "extends": "base", "animal": "a pale cat", "description": "pale spots",
        "source": "a field guide", "colours": {"B": [0.7, 0.65, 0.55]},
        "melanins": {"B": {"pheomelanin": 0.2}}})");
    const Preset b = load_preset_file(tmp.file("base.json"));
    const Preset p = load_preset_file(child);
    EXPECT_EQ(p.name, "pale");
    EXPECT_EQ(p.animal, "a pale cat");
    EXPECT_EQ(p.description, "pale spots");
    EXPECT_EQ(p.extends, "base");
    EXPECT_EQ(b.extends, "");
    ASSERT_EQ(p.types.size(), 2);
    // The overridden type has the new colour and pheomelanin, the rest the base's.
    EXPECT_FLOAT_EQ(p.types[1].colour[0], 0.7f);
    EXPECT_FLOAT_EQ(p.types[1].colour[2], 0.55f);
    EXPECT_FLOAT_EQ(p.types[1].pheomelanin, 0.2f);
    EXPECT_FLOAT_EQ(p.types[1].eumelanin, 0.05f);
    EXPECT_FLOAT_EQ(p.types[0].colour[0], 0.02f);
    EXPECT_DOUBLE_EQ(p.types[1].division_time, 60);
    EXPECT_DOUBLE_EQ(p.types.alpha(0, 0), 0.8);
    EXPECT_DOUBLE_EQ(p.params.w_r, b.params.w_r);
    EXPECT_DOUBLE_EQ(p.params.rho, b.params.rho);
    EXPECT_EQ(p.params.initial_cells, b.params.initial_cells);
    // The stored text stands alone (a .cells file keeps it): no "extends", and the
    // base's published counts stay with the base.
    const auto j = nlohmann::json::parse(p.json_text);
    EXPECT_FALSE(j.contains("extends"));
    EXPECT_FALSE(j.contains("published"));
    EXPECT_EQ(j["notes"], "base notes");
    EXPECT_EQ(j["source"], "a field guide");
    const Preset again = parse_preset(p.json_text, tmp.file("elsewhere/x.json"));
    EXPECT_FLOAT_EQ(again.types[1].colour[1], 0.65f);
    // By name, as `--preset pale` finds it.
    EXPECT_EQ(load_preset("pale", tmp.path().string()).types[1].colour[1], 0.65f);
}

struct BadChild {
    std::string json, message;
};

TEST(PresetExtends, RefusesWhatItCannotTakeNamingTheField) {
    test::TempDir tmp;
    tmp.write("base.json", base_json);
    tmp.write("chained.json",
              R"({"name": "chained", "extends": "base", "colours": {"F": [0, 0, 0]}})");
    const std::vector<BadChild> cases = {
        {R"({"name": "c", "extends": "base", "colours": {"b": [0.5, 0.5, 0.5]}})",
         "colours.b: 'b' is not a type of 'base' (did you mean 'B'?); its types: F, B"},
        {R"({"name": "c", "extends": "base", "colours": {"B": [0.5, -0.1, 0.5]}})",
         "colours.B: components must be >= 0"},
        {R"({"name": "c", "extends": "base", "colours": {"B": [0.5, 0.5]}})",
         "colours.B: expected 3 numbers"},
        {R"({"name": "c", "extends": "base", "colours": {}})",
         "colours: expected an object"},
        {R"({"name": "c", "extends": "base"})", "colours: missing"},
        {R"({"name": "c", "extends": "base", "colours": {"B": [1, 1, 1]},
            "simulation": {"w_r": 3}})",
         "simulation: unknown key"},
        {R"({"name": "c", "extends": "base", "colors": {"B": [1, 1, 1]},
            "colours": {"B": [1, 1, 1]}})",
         "colours: given twice"},
        {R"({"name": "c", "extends": "base", "colours": {"B": [1, 1, 1]},
            "melanins": {"B": {"eumelanin": -1}}})",
         "melanins.B.eumelanin: must be >= 0"},
        {R"({"name": "c", "extends": "base", "colours": {"B": [1, 1, 1]},
            "melanins": {"B": {"melanin": 1}}})",
         "melanins.B.melanin: unknown key"},
        {R"({"name": "c", "extends": "bass", "colours": {"B": [1, 1, 1]}})",
         "extends: 'bass': no preset"},
        {R"({"name": "c", "extends": "../base", "colours": {"B": [1, 1, 1]}})",
         "extends: '../base': expected the name of a preset (no path, no .json)"},
        {R"({"name": "c", "extends": 3, "colours": {"B": [1, 1, 1]}})",
         "extends: expected the name of a preset"},
        {R"({"extends": "base", "colours": {"B": [1, 1, 1]}})", "name: missing"},
        {R"({"name": "c", "extends": "chained", "colours": {"B": [1, 1, 1]}})",
         "extends: 'chained' itself extends 'base'"},
    };
    for (const BadChild &c : cases) {
        const std::string path = tmp.write("child.json", c.json);
        const std::string msg = what(path);
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find(c.message), std::string::npos) << c.json << "\n" << msg;
    }
}

TEST(PresetExtends, AFileElsewhereExtendsAShippedPreset) {
    test::TempDir shipped, mine;
    shipped.write("base.json", base_json);
    const std::string child = mine.write(
        "mine.json",
        R"({"name": "mine", "extends": "base", "colours": {"F": [0.1, 0.05, 0.02]}})");
    const std::string dir = shipped.path().string();
    EXPECT_FLOAT_EQ(load_preset_file(child, dir).types[0].colour[1], 0.05f);
    // As `--preset mine.json` reads it, with the shipped folder to fall back on.
    EXPECT_FLOAT_EQ(load_preset(child, dir).types[0].colour[0], 0.1f);
    // Without it the base is looked for beside the file only.
    const std::string msg = what(child);
    EXPECT_NE(msg.find("extends: 'base': no preset " + mine.file("base.json")),
              std::string::npos)
        << msg;
    // One beside the file comes first.
    mine.write("base.json", std::string(base_json).replace(
                                std::string(base_json).find("0.62, 0.36, 0.11"), 16,
                                "0.30, 0.36, 0.11"));
    EXPECT_FLOAT_EQ(load_preset_file(child, dir).types[1].colour[0], 0.30f);
}

TEST(PresetExtends, ShippedAliasesKeepTheirBaseCellsAndChangeItsColours) {
    const std::string dir = test::source_path("scenes/presets");
    size_t aliases = 0;
    for (const std::string &name : preset_names(dir)) {
        const Preset p = load_preset(name, dir);
        if (p.extends.empty()) continue;
        ++aliases;
        const Preset b = load_preset(p.extends, dir);
        EXPECT_FALSE(p.animal.empty()) << name;
        ASSERT_EQ(p.types.size(), b.types.size()) << name;
        bool changed = false;
        for (int i = 0; i < p.types.size(); ++i) {
            EXPECT_EQ(p.types[i].name, b.types[i].name) << name;
            EXPECT_EQ(p.types[i].division_time, b.types[i].division_time) << name;
            for (int k = 0; k < 3; ++k)
                changed |= p.types[i].colour[k] != b.types[i].colour[k];
        }
        EXPECT_TRUE(changed) << name << " has its base's colours";
        EXPECT_EQ(p.params.w_r, b.params.w_r) << name;
        EXPECT_EQ(p.params.end_time, b.params.end_time) << name;
    }
    EXPECT_GE(aliases, 8u);
}

}  // namespace
}  // namespace pelage::sim
