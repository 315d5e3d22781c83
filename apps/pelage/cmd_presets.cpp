// `pelage presets [NAME]`: the shipped presets, each with its description and source
// (the preset file's own "description" and "source"), or one preset's notes too.
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

// A preset file's own words: its description, source and notes ("" where it has none).
struct PresetText {
    std::string name, description, source, notes;
};

PresetText preset_text(const std::string &dir, const std::string &name) {
    // Parsed as a preset first, so a broken one is an error naming it, not a blank row.
    sim::load_preset(name, dir);
    std::ifstream in(dir + "/" + name + ".json");
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    auto text = [&](const char *key) {
        return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
    };
    return {name, text("description"), text("source"), text("notes")};
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
                                    {"description", p.description},
                                    {"source", p.source},
                                    {"notes", p.notes}});
        std::cout << j.dump(2) << std::endl;
        return 0;
    }
    for (const PresetText &p : presets) {
        std::printf("%s\n  %s\n", p.name.c_str(), p.description.c_str());
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
        "presets", "List the shipped presets with their descriptions and sources");
    sub->add_option("name", o->name, "Show only this preset, with its notes");
    sub->add_flag("--json", o->json, "Print JSON instead of text");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
