// `pelage presets [NAME]`: the shipped presets, each with its animal, description and
// source (the preset file's own "animal", "description" and "source"; the preset it
// extends, if any), or one preset's notes too.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "sim/core/input_error.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

struct PresetsOptions {
    std::string name;
    bool json = false;
};

// A preset file's own words: its animal, description, source and notes ("" where it has
// none), and the preset it extends.
struct PresetText {
    std::string name, animal, description, source, notes, extends;
};

PresetText preset_text(const std::string &dir, const std::string &name) {
    // Parsed as a preset first, so a broken one is an error naming it, not a blank row.
    const sim::Preset preset = sim::load_preset(name, dir);
    std::ifstream in(dir + "/" + name + ".json");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    auto text = [&](const char *key) {
        return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
    };
    return {name,           text("animal"), text("description"),
            text("source"), text("notes"),  preset.extends};
}

int run(const PresetsOptions &o) {
    const std::string dir = data_path("scenes/presets");
    std::vector<std::string> names = sim::preset_names(dir);
    if (!o.name.empty()) {
        sim::load_preset(o.name, dir, "",
                         "NAME");  // an unknown name: the error lists them
        names = {o.name};
    }
    std::vector<PresetText> presets;
    for (const std::string &n : names) presets.push_back(preset_text(dir, n));
    if (o.json) {
        nlohmann::json j = {{"folder", dir}, {"presets", nlohmann::json::array()}};
        for (const PresetText &p : presets)
            j["presets"].push_back({{"name", p.name},
                                    {"animal", p.animal},
                                    {"extends", p.extends},
                                    {"description", p.description},
                                    {"source", p.source},
                                    {"notes", p.notes}});
        std::cout << j.dump(2) << std::endl;
        return 0;
    }
    for (const PresetText &p : presets) {
        std::printf("%s\n", p.name.c_str());
        if (!p.animal.empty()) std::printf("  animal: %s\n", p.animal.c_str());
        std::printf("  %s\n", p.description.c_str());
        if (!p.extends.empty())
            std::printf("  extends: %s (its cells, with these colours)\n",
                        p.extends.c_str());
        if (!p.source.empty()) std::printf("  source: %s\n", p.source.c_str());
        if (!o.name.empty() && !p.notes.empty())
            std::printf("  notes: %s\n", p.notes.c_str());
    }
    return 0;
}

}  // namespace

Runner add_presets_command(CLI::App &app) {
    auto o = std::make_shared<PresetsOptions>();
    CLI::App *sub = app.add_subcommand(
        "presets",
        "List the shipped presets with their animals, descriptions and sources");
    sub->add_option("name", o->name, "Show only this preset, with its notes");
    sub->add_flag("--json", o->json, "Print JSON instead of text");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
