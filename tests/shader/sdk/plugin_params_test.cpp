// The shipped C++ plugins read their parameters by name and refuse, through the ABI's
// error, a parameter set that disagrees with their table: a value of another type is a
// message naming it, never a misread; values out of table order are read by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "tests/shader/plugin_mesh_view.h"

namespace pelage::test {
namespace {

renderer::LoadedPlugin load(const std::string &name) {
    return renderer::open_plugin(renderer::package_lib_dir() + "/shaders/" + name +
                                 ".so");
}

struct Created {
    void *self = nullptr;
    std::string error;
};

Created create(const renderer::LoadedPlugin &p, const std::vector<PelageParamValue> &v,
               const char *cells = nullptr) {
    const PluginMeshView view(PluginMeshView::unit_triangle(), "procedural:test", cells);
    PelageParamSet ps{};
    ps.count = uint32_t(v.size());
    ps.values = v.data();
    ps.mesh = view.view;
    ps.warn = PluginMeshView::warn;
    ps.scene_dir = "";
    PelageError err{};
    Created c;
    c.self = p.desc->create(&ps, &err);
    c.error = err.message;
    return c;
}

// Another type than `t`, with the value left as it is.
PelageParamType other_type(PelageParamType t) {
    return t == PELAGE_PARAM_FLOAT ? PELAGE_PARAM_INT : PELAGE_PARAM_FLOAT;
}

PelageShade shade(const renderer::LoadedPlugin &p, const void *self) {
    PelageHit hit{};
    hit.b1 = 0.3f;
    hit.b2 = 0.2f;
    hit.footprint = 1e-3f;
    PelageShade out{};
    p.desc->shade(self, &hit, &out);
    return out;
}

TEST(ShaderSdkPlugins, ProceduralPluginsRefuseEveryMistypedParameter) {
    for (const char *name : {"worley", "perlin"}) {
        const renderer::LoadedPlugin p = load(name);
        const renderer::PluginParams params = renderer::validate_plugin_params(
            *p.desc, nlohmann::json::object(), "test.json", "params");
        ASSERT_FALSE(params.values.empty());
        for (size_t k = 0; k < params.values.size(); ++k) {
            std::vector<PelageParamValue> v = params.values;
            v[k].type = other_type(v[k].type);
            const Created c = create(p, v);
            EXPECT_EQ(c.self, nullptr) << name << " " << v[k].name;
            EXPECT_NE(c.error.find(std::string("\"") + v[k].name + "\""),
                      std::string::npos)
                << name << ": " << c.error;
            if (c.self) p.desc->destroy(c.self);
        }
    }
}

TEST(ShaderSdkPlugins, ProceduralPluginsReadByNameInAnyOrder) {
    for (const char *name : {"worley", "perlin"}) {
        const renderer::LoadedPlugin p = load(name);
        // Non-default values, so that a value read from the wrong entry shows.
        const nlohmann::json j = {{"frequency", 3.5},
                                  {"spot_colour", {0.9, 0.1, 0.2}},
                                  {"base_colour", {0.05, 0.6, 0.7}},
                                  {"seed", 9}};
        const renderer::PluginParams params =
            renderer::validate_plugin_params(*p.desc, j, "test.json", "params");
        std::vector<PelageParamValue> reversed = params.values;
        std::reverse(reversed.begin(), reversed.end());
        const Created a = create(p, params.values), b = create(p, reversed);
        ASSERT_NE(a.self, nullptr) << a.error;
        ASSERT_NE(b.self, nullptr) << b.error;
        const PelageShade sa = shade(p, a.self), sb = shade(p, b.self);
        EXPECT_EQ(std::memcmp(&sa, &sb, sizeof sa), 0) << name;
        p.desc->destroy(a.self);
        p.desc->destroy(b.self);
    }
}

TEST(ShaderSdkPlugins, TextureAndMosaicRefuseAMistypedParameter) {
    const renderer::LoadedPlugin texture = load("texture");
    renderer::PluginParams tp = renderer::validate_plugin_params(
        *texture.desc, {{"file", "image.exr"}}, "test.json", "params");
    tp.values[0].type = PELAGE_PARAM_INT;
    const Created t = create(texture, tp.values);
    EXPECT_EQ(t.self, nullptr);
    EXPECT_EQ(t.error,
              "parameter \"file\" is string in the plugin's table, int in the "
              "parameter set");

    const renderer::LoadedPlugin mosaic = load("clonal_mosaic");
    renderer::PluginParams mp = renderer::validate_plugin_params(
        *mosaic.desc, nlohmann::json::object(), "test.json", "params");
    for (PelageParamValue &v : mp.values)
        if (std::string(v.name) == "jitter") v.type = PELAGE_PARAM_RGB;
    const Created m = create(mosaic, mp.values, "unread.cells");
    EXPECT_EQ(m.self, nullptr);
    EXPECT_EQ(m.error,
              "parameter \"jitter\" is float in the plugin's table, rgb in the "
              "parameter set");
}

}  // namespace
}  // namespace pelage::test
