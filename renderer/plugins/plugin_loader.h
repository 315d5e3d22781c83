// Finding and opening shader plugins (shader/pelage_shader.h). The search path is
// $PELAGE_SHADER_PATH (colon-separated folders, searched first), then lib/pelage/shaders
// next to the executable's bin/ folder (renderer/core/install_layout.h; the same folder
// in a build tree). A plugin file is `<name>.so`; its descriptor's ABI version is
// checked before anything else in it is used.
#pragma once

#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shader/pelage_shader.h"

namespace pelage::renderer {

struct LoadedPlugin {
    std::string file;
    const PelageShaderPlugin *desc = nullptr;
};

// Opens one plugin file. Throws std::runtime_error naming the file when it cannot be
// opened, lacks the entry symbol, or has another ABI version.
LoadedPlugin open_plugin(const std::string &file);

class PluginRegistry {
  public:
    // Scans the search path once (later folders never shadow earlier ones).
    PluginRegistry();
    explicit PluginRegistry(std::vector<std::string> dirs);

    static std::vector<std::string> default_search_path();

    // The plugin called `name`; throws pelage::InputError (file `scene_file`, `field`)
    // for an unknown name, and std::runtime_error naming the file for a refused one.
    const LoadedPlugin &get(const std::string &name, const std::string &scene_file,
                            const std::string &field) const;
    const std::map<std::string, LoadedPlugin> &plugins() const { return m_plugins; }
    // Files that were found but refused, with the reason.
    const std::map<std::string, std::string> &refused() const { return m_refused; }
    const std::vector<std::string> &dirs() const { return m_dirs; }

  private:
    void scan();
    std::vector<std::string> m_dirs;
    std::map<std::string, LoadedPlugin> m_plugins;
    std::map<std::string, std::string> m_refused;  // name (file stem) -> message
};

// Parameters validated against a plugin's table, in table order, defaults filled in;
// owns the strings the values point at.
struct PluginParams {
    std::vector<PelageParamValue> values;
    std::deque<std::string> strings;
    PluginParams() = default;
    PluginParams(const PluginParams &) = delete;
    PluginParams &operator=(const PluginParams &) = delete;
    PluginParams(PluginParams &&) = default;
};

// Checks `params` (a JSON object) against the plugin's table: unknown keys, types and
// ranges are pelage::InputError at `field_prefix.<key>` in `scene_file`.
PluginParams validate_plugin_params(const PelageShaderPlugin &plugin,
                                    const nlohmann::json &params,
                                    const std::string &scene_file,
                                    const std::string &field_prefix);

const char *param_type_name(PelageParamType t);

}  // namespace pelage::renderer
