// `pelage shaders [NAME]`: the installed shader plugins and their parameters (the
// plugins' own tables are their documentation).
#include <cstdio>
#include <iostream>
#include <memory>

#include "renderer/cli/common.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/core/input_error.h"

namespace pelage::cli {
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
        list.push_back(&registry.get(o.name, "", "shader"));
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
    std::printf("search path:");
    for (const auto &d : registry.dirs()) std::printf(" %s", d.c_str());
    std::printf("\n");
    if (list.empty()) std::printf("no shader plugins found\n");
    for (const LoadedPlugin *p : list) {
        std::printf("\n%s - %s\n  file: %s\n", p->desc->name,
                    p->desc->summary ? p->desc->summary : "", p->file.c_str());
        for (const PelageParamSpec *s = p->desc->params; s->name; ++s) {
            std::printf("  %-16s %-6s default %-18s", s->name, param_type_name(s->type),
                        default_text(*s).c_str());
            if (s->min_value < s->max_value)
                std::printf(" in [%g, %g]", s->min_value, s->max_value);
            std::printf("  %s\n", s->doc ? s->doc : "");
        }
        if (p->desc->aov_names)
            for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && p->desc->aov_names[k]; ++k)
                std::printf("  AOV shader.%s\n", p->desc->aov_names[k]);
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

}  // namespace pelage::cli
