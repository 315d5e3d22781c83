// `pelage shaders [NAME]`: the installed shader plugins and their parameters. A
// plugin's parameter table (shader/pelage_shader.h) is its documentation: this prints
// it as it is, so no copy of it exists to drift.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

using namespace pelage::renderer;

struct ShadersOptions {
    std::string name;
    bool json = false;
};

std::string default_text(const PelageParamSpec &s) {
    char buf[128];
    switch (s.type) {
        case PELAGE_PARAM_FLOAT:
            std::snprintf(buf, sizeof buf, "%g", s.default_value[0]);
            break;
        case PELAGE_PARAM_INT:
            std::snprintf(buf, sizeof buf, "%d", int(s.default_value[0]));
            break;
        case PELAGE_PARAM_RGB:
            std::snprintf(buf, sizeof buf, "[%g, %g, %g]", s.default_value[0],
                          s.default_value[1], s.default_value[2]);
            break;
        case PELAGE_PARAM_STRING:
            std::snprintf(buf, sizeof buf, "\"%s\"",
                          s.default_string ? s.default_string : "");
            break;
    }
    return buf;
}

// The inclusive range as the table holds it; "" when it has none (strings).
std::string range_text(const PelageParamSpec &s) {
    if (!(s.min_value < s.max_value)) return "";
    char buf[96];
    if (s.type == PELAGE_PARAM_INT)
        std::snprintf(buf, sizeof buf, "[%.0f, %.0f]", double(s.min_value),
                      double(s.max_value));
    else
        std::snprintf(buf, sizeof buf, "[%g, %g]", double(s.min_value),
                      double(s.max_value));
    return buf;
}

// One plugin: its summary, file, parameter table (a row per entry, columns aligned) and
// AOV names.
void print_plugin(const LoadedPlugin &p) {
    std::printf("%s - %s\n  file: %s\n", p.desc->name,
                p.desc->summary ? p.desc->summary : "", p.file.c_str());
    std::vector<std::vector<std::string>> rows = {
        {"parameter", "type", "default", "range", "description"}};
    for (const PelageParamSpec *s = p.desc->params; s && s->name; ++s)
        rows.push_back({s->name, param_type_name(s->type), default_text(*s),
                        range_text(*s), s->doc ? s->doc : ""});
    if (rows.size() == 1) {
        std::printf("  no parameters\n");
    } else {
        size_t width[4] = {0, 0, 0, 0};
        for (const auto &r : rows)
            for (size_t c = 0; c < 4; ++c) width[c] = std::max(width[c], r[c].size());
        for (const auto &r : rows) {
            std::printf(" ");
            for (size_t c = 0; c < 4; ++c)
                std::printf(" %-*s ", int(width[c]), r[c].c_str());
            std::printf(" %s\n", r[4].c_str());
        }
    }
    std::string aovs;
    if (p.desc->aov_names)
        for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && p.desc->aov_names[k]; ++k)
            aovs +=
                std::string(aovs.empty() ? "" : ", ") + "shader." + p.desc->aov_names[k];
    std::printf("  AOVs: %s\n", aovs.empty() ? "none" : aovs.c_str());
}

// The plugin called `name`: an unknown name is bad input (exit 2), naming what is
// installed and where it was looked for.
const LoadedPlugin &find_plugin(const PluginRegistry &registry, const std::string &name) {
    if (registry.plugins().count(name) || registry.refused().count(name))
        return registry.get(name, "", "shader");  // throws for a refused one
    std::string installed, dirs;
    for (const auto &[n, p] : registry.plugins())
        installed += (installed.empty() ? "" : ", ") + n;
    for (const auto &d : registry.dirs()) dirs += (dirs.empty() ? "" : ":") + d;
    throw InputError("", 0, "NAME",
                     "no shader plugin \"" + name + "\" (installed: " +
                         (installed.empty() ? std::string("none") : installed) +
                         "; searched " + (dirs.empty() ? std::string("nothing") : dirs) +
                         ", $PELAGE_SHADER_PATH first)");
}

nlohmann::json plugin_json(const LoadedPlugin &p) {
    nlohmann::json params = nlohmann::json::array();
    for (const PelageParamSpec *s = p.desc->params; s->name; ++s) {
        nlohmann::json j = {{"name", s->name},
                            {"type", param_type_name(s->type)},
                            {"doc", s->doc ? s->doc : ""}};
        if (s->type == PELAGE_PARAM_STRING)
            j["default"] = s->default_string ? s->default_string : "";
        else if (s->type == PELAGE_PARAM_RGB)
            j["default"] = {s->default_value[0], s->default_value[1],
                            s->default_value[2]};
        else if (s->type == PELAGE_PARAM_INT)
            j["default"] = int(s->default_value[0]);
        else
            j["default"] = s->default_value[0];
        if (s->min_value < s->max_value) j["range"] = {s->min_value, s->max_value};
        params.push_back(j);
    }
    nlohmann::json aovs = nlohmann::json::array();
    if (p.desc->aov_names)
        for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && p.desc->aov_names[k]; ++k)
            aovs.push_back(p.desc->aov_names[k]);
    return {{"name", p.desc->name}, {"summary", p.desc->summary ? p.desc->summary : ""},
            {"file", p.file},       {"abi", p.desc->abi},
            {"params", params},     {"aovs", aovs}};
}

int run(const ShadersOptions &o) {
    const PluginRegistry registry;
    std::vector<const LoadedPlugin *> list;
    if (!o.name.empty())
        list.push_back(&find_plugin(registry, o.name));
    else
        for (const auto &[name, p] : registry.plugins()) list.push_back(&p);
    if (o.json) {
        nlohmann::json j = {{"search_path", registry.dirs()},
                            {"shaders", nlohmann::json::array()}};
        for (const LoadedPlugin *p : list) j["shaders"].push_back(plugin_json(*p));
        nlohmann::json refused = nlohmann::json::object();
        for (const auto &[name, why] : registry.refused()) refused[name] = why;
        j["refused"] = refused;
        std::cout << j.dump(2) << std::endl;
        return 0;
    }
    if (!o.name.empty()) {
        print_plugin(*list[0]);
        return 0;
    }
    std::printf("search path:");
    for (const auto &d : registry.dirs()) std::printf(" %s", d.c_str());
    std::printf("\n");
    if (list.empty()) std::printf("no shader plugins found\n");
    for (const LoadedPlugin *p : list) {
        std::printf("\n");
        print_plugin(*p);
    }
    if (o.name.empty())
        for (const auto &[name, why] : registry.refused())
            std::printf("\nrefused: %s\n", why.c_str());
    return 0;
}

}  // namespace

Runner add_shaders_command(CLI::App &app) {
    auto o = std::make_shared<ShadersOptions>();
    CLI::App *sub = app.add_subcommand(
        "shaders", "List installed shader plugins and their parameters");
    sub->add_option("name", o->name, "Show only this plugin");
    sub->add_flag("--json", o->json, "Print JSON instead of text");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
