// libFuzzer target: the shader parameter parser (validate_plugin_params in
// renderer/plugins/plugin_loader.cpp), which checks a material's "params" object against
// a plugin's PelageParamSpec table. The table below has one entry of every type, with and
// without a range, as the shipped plugins declare them. Bad input must end in
// pelage::InputError; any other exception, crash or sanitizer report is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "renderer/plugins/plugin_loader.h"
#include "sim/core/input_error.h"

namespace {

const PelageParamSpec specs[] = {
    {"jitter", PELAGE_PARAM_FLOAT, {0, 0, 0}, nullptr, 0.0f, 1.0f, "ranged float"},
    {"scale", PELAGE_PARAM_FLOAT, {1, 0, 0}, nullptr, 0.0f, 0.0f, "unranged float"},
    {"antialias", PELAGE_PARAM_INT, {1, 0, 0}, nullptr, 0.0f, 1.0f, "ranged int"},
    {"octaves", PELAGE_PARAM_INT, {4, 0, 0}, nullptr, 0.0f, 0.0f, "unranged int"},
    {"color", PELAGE_PARAM_RGB, {0.5f, 0.5f, 0.5f}, nullptr, 0.0f, 1.0f, "ranged rgb"},
    {"neighbourhood", PELAGE_PARAM_STRING, {0, 0, 0}, "geodesic", 0.0f, 0.0f, "string"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

const PelageShaderPlugin plugin = {PELAGE_SHADER_ABI, "fuzz",  "fuzz target", specs,
                                   nullptr,           nullptr, nullptr,       nullptr,
                                   nullptr,           nullptr};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    // The scene loader hands over only objects; anything else is its error, not ours.
    const nlohmann::json params =
        nlohmann::json::parse(data, data + size, nullptr, false);
    if (!params.is_object()) return 0;
    try {
        const pelage::renderer::PluginParams p = pelage::renderer::validate_plugin_params(
            plugin, params, "/fuzz/scene.json", "objects[0].material.params");
        // Every accepted value is in its table's range and finite.
        for (size_t k = 0; k < p.values.size(); ++k) {
            const PelageParamSpec &s = specs[k];
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(p.values[k].f[c])) __builtin_trap();
                if (s.min_value < s.max_value && s.type != PELAGE_PARAM_STRING &&
                    (p.values[k].f[c] < s.min_value || p.values[k].f[c] > s.max_value) &&
                    (c == 0 || s.type == PELAGE_PARAM_RGB))
                    __builtin_trap();
            }
        }
    } catch (const pelage::InputError &) {
    }
    return 0;
}
