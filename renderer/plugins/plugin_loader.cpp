#include "renderer/plugins/plugin_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "renderer/core/install_layout.h"
#include "shader/sdk/params.h"
#include "sim/core/colour_spelling.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

LoadedPlugin open_plugin(const std::string &file) {
    // RTLD_LOCAL: plugins never see each other's symbols.
    void *handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char *e = dlerror();
        throw std::runtime_error(
            file + ": cannot load shader plugin: " + (e ? e : "unknown error"));
    }
    auto entry = reinterpret_cast<PelageShaderEntry>(dlsym(handle, PELAGE_SHADER_ENTRY));
    if (!entry) {
        dlclose(handle);
        throw std::runtime_error(
            file + ": not a pelage shader plugin (no symbol `" PELAGE_SHADER_ENTRY "`)");
    }
    const PelageShaderPlugin *desc = entry();
    if (!desc) {
        dlclose(handle);
        throw std::runtime_error(file + ": " PELAGE_SHADER_ENTRY "() returned NULL");
    }
    // The version is checked before anything else in the descriptor is read.
    if (desc->abi != PELAGE_SHADER_ABI) {
        const unsigned abi = desc->abi;
        dlclose(handle);
        throw std::runtime_error(file + ": shader plugin ABI version " +
                                 std::to_string(abi) + ", this pelage needs " +
                                 std::to_string(PELAGE_SHADER_ABI) +
                                 " (rebuild the plugin against shader/pelage_shader.h)");
    }
    if (!desc->name || !desc->create || !desc->shade || !desc->destroy || !desc->params) {
        dlclose(handle);
        throw std::runtime_error(
            file +
            ": shader plugin descriptor is incomplete (name, params, "
            "create, shade and destroy are required)");
    }
    // The handle stays open for the life of the process: instances may outlive a
    // registry.
    return {file, desc};
}

std::vector<std::string> PluginRegistry::default_search_path() {
    std::vector<std::string> dirs;
    if (const char *env = std::getenv("PELAGE_SHADER_PATH"); env && *env) {
        std::stringstream ss(env);
        std::string d;
        while (std::getline(ss, d, ':'))
            if (!d.empty()) dirs.push_back(d);
    }
    if (const std::string lib = package_lib_dir(); !lib.empty())
        dirs.push_back((fs::path(lib) / "shaders").string());
    return dirs;
}

PluginRegistry::PluginRegistry() : PluginRegistry(default_search_path()) {}

PluginRegistry::PluginRegistry(std::vector<std::string> dirs) : m_dirs(std::move(dirs)) {
    scan();
}

void PluginRegistry::scan() {
    for (const auto &dir : m_dirs) {
        std::error_code ec;
        std::vector<fs::path> files;
        for (const auto &e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".so") files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const auto &f : files) {
            const std::string stem = f.stem().string();
            if (m_plugins.count(stem) || m_refused.count(stem))
                continue;  // earlier folder wins
            try {
                LoadedPlugin p = open_plugin(f.string());
                const std::string name = p.desc->name;
                if (!m_plugins.count(name)) m_plugins.emplace(name, std::move(p));
            } catch (const std::exception &e) {
                m_refused.emplace(stem, e.what());
            }
        }
    }
}

const LoadedPlugin &PluginRegistry::get(const std::string &name,
                                        const std::string &scene_file,
                                        const std::string &field) const {
    if (auto it = m_plugins.find(name); it != m_plugins.end()) return it->second;
    if (auto it = m_refused.find(name); it != m_refused.end())
        throw std::runtime_error(it->second);
    std::string dirs;
    for (const auto &d : m_dirs) dirs += (dirs.empty() ? "" : ":") + d;
    throw InputError(scene_file, 0, field,
                     "unknown shader \"" + name + "\" (no " + name + ".so in " +
                         (dirs.empty() ? std::string("an empty search path") : dirs) +
                         "; see `pelage shaders`, $PELAGE_SHADER_PATH)");
}

const char *param_type_name(PelageParamType t) { return shader::sdk::type_name(t); }

PluginParams validate_plugin_params(const PelageShaderPlugin &plugin,
                                    const nlohmann::json &params,
                                    const std::string &scene_file,
                                    const std::string &prefix) {
    PluginParams out;
    auto fail = [&](const std::string &key, const std::string &msg) {
        throw InputError(scene_file, 0, prefix + "." + key, msg);
    };
    size_t known = 0;
    for (const PelageParamSpec *s = plugin.params; s->name; ++s) {
        // Found in either spelling of "colour", and named as the scene spells it.
        const std::string key =
            spelling_in(params, s->name, scene_file, prefix + "." + s->name);
        PelageParamValue v{};
        v.name = s->name;
        v.type = s->type;
        for (int c = 0; c < 3; ++c) v.f[c] = s->default_value[c];
        v.i = int32_t(s->default_value[0]);
        const bool has_range = s->min_value < s->max_value;
        auto check = [&](const nlohmann::json &x, const std::string &what) -> float {
            if (!x.is_number()) fail(key, "expected a number" + what);
            const double d = x.get<double>();
            // Beyond FLT_MAX the float handed to the plugin would be infinite.
            if (!std::isfinite(d) || std::fabs(d) > double(FLT_MAX) ||
                (has_range && (d < s->min_value || d > s->max_value))) {
                std::ostringstream m;
                m << "= " << d << ": must be in [" << s->min_value << ", " << s->max_value
                  << "]";
                fail(key, m.str());
            }
            return float(d);
        };
        if (auto it = params.find(key); it != params.end()) {
            ++known;
            const nlohmann::json &x = *it;
            switch (s->type) {
                case PELAGE_PARAM_FLOAT:
                    v.f[0] = check(x, "");
                    break;
                case PELAGE_PARAM_INT:
                    if (!x.is_number_integer()) fail(key, "expected an integer");
                    {
                        const float f = check(x, "");
                        // Casting a float outside int32's range is undefined behaviour.
                        if (!(f >= -2147483648.0f && f < 2147483648.0f))
                            fail(key, "= " + x.dump() + ": out of the integer range");
                        v.i = int32_t(f);
                    }
                    v.f[0] = float(v.i);
                    break;
                case PELAGE_PARAM_RGB:
                    if (x.is_number()) {
                        v.f[0] = v.f[1] = v.f[2] = check(x, "");
                    } else {
                        if (!x.is_array() || x.size() != 3)
                            fail(key, "expected [r, g, b] or one number");
                        for (int c = 0; c < 3; ++c) v.f[c] = check(x[c], " in [r, g, b]");
                    }
                    break;
                case PELAGE_PARAM_STRING:
                    // An object goes to the plugin as its JSON text (e.g.
                    // clonal_mosaic's "types").
                    if (!x.is_string() && !x.is_object()) fail(key, "expected a string");
                    out.strings.push_back(x.is_string() ? x.get<std::string>()
                                                        : x.dump());
                    v.s = out.strings.back().c_str();
                    break;
            }
        } else if (s->type == PELAGE_PARAM_STRING) {
            out.strings.push_back(s->default_string ? s->default_string : "");
            v.s = out.strings.back().c_str();
        }
        out.values.push_back(v);
    }
    if (known != params.size()) {
        for (auto it = params.begin(); it != params.end(); ++it) {
            bool found = false;
            for (const PelageParamSpec *s = plugin.params; s->name; ++s)
                found |=
                    it.key() == s->name || other_colour_spelling(it.key()) == s->name;
            if (!found)
                fail(it.key(),
                     std::string("unknown parameter of shader \"") + plugin.name + "\"");
        }
    }
    return out;
}

}  // namespace pelage::renderer
