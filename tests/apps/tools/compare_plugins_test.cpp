// What `pelage compare` knows of a shader comes from the plugin's own parameter table and
// AOV names, never its name: a renamed plugin with the same table is matched the same
// way, and the noise AOV is found by name in whatever slot it occupies.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "apps/tools/compare.h"
#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using renderer::BaselineModel;

renderer::LoadedPlugin load(const std::string &name) {
    return renderer::open_plugin(renderer::package_lib_dir() + "/shaders/" + name +
                                 ".so");
}

TEST(ComparePlugins, ShippedPluginsByTheirTables) {
    const auto worley = load("worley"), perlin = load("perlin"),
               texture = load("texture"), mosaic = load("clonal_mosaic"),
               diffuse = load("diffuse");
    EXPECT_EQ(renderer::baseline_model(*worley.desc), BaselineModel::cellular);
    EXPECT_EQ(renderer::baseline_model(*perlin.desc), BaselineModel::thresholded_noise);
    for (const auto *p : {&texture, &mosaic, &diffuse})
        EXPECT_EQ(renderer::baseline_model(*p->desc), BaselineModel::none) << p->file;
    EXPECT_TRUE(renderer::maps_image_by_uv(*texture.desc));
    for (const auto *p : {&worley, &perlin, &mosaic, &diffuse})
        EXPECT_FALSE(renderer::maps_image_by_uv(*p->desc)) << p->file;
    EXPECT_EQ(renderer::aov_slot(*perlin.desc, "noise"), 0);
    EXPECT_EQ(renderer::aov_slot(*worley.desc, "feature"), 2);
    EXPECT_EQ(renderer::aov_slot(*worley.desc, "noise"), -1);
    EXPECT_EQ(renderer::aov_slot(*texture.desc, "noise"), -1);  // no AOVs at all
}

TEST(ComparePlugins, ARenamedPluginIsMatchedByItsTable) {
    const auto perlin = load("perlin");
    const char *const aovs[] = {"grain", "noise", nullptr};
    PelageShaderPlugin renamed = *perlin.desc;
    renamed.name = "my_fbm";
    renamed.aov_names = aovs;
    EXPECT_EQ(renderer::baseline_model(renamed), BaselineModel::thresholded_noise);
    EXPECT_EQ(renderer::aov_slot(renamed, "noise"), 1);
    // Without a noise AOV to threshold, there is nothing to match.
    renamed.aov_names = nullptr;
    EXPECT_EQ(renderer::baseline_model(renamed), BaselineModel::none);
}

TEST(ComparePlugins, MatchedParamsFollowTheModel) {
    TempDir tmp;
    const std::string cells =
        simulate_two_type_cells(tmp, "procedural:icosphere:3", 300, 0.3, 5);
    PelageShaderPlugin cellular = *load("worley").desc, noise = *load("perlin").desc;
    cellular.name = "cells_under_another_name";
    noise.name = "noise_under_another_name";
    const nlohmann::json c = renderer::matched_baseline_params(cellular, cells),
                         n = renderer::matched_baseline_params(noise, cells);
    for (const auto *j : {&c, &n}) {
        EXPECT_TRUE(j->contains("spot_colour")) << *j;
        EXPECT_TRUE(j->contains("base_colour")) << *j;
        EXPECT_GT((*j)["frequency"].get<double>(), 0.0) << *j;
        EXPECT_GT((*j)["spot_fraction"].get<double>(), 0.0) << *j;
    }
    EXPECT_TRUE(c.contains("mean_points")) << c;
    EXPECT_FALSE(n.contains("mean_points")) << n;
    EXPECT_TRUE(renderer::matched_baseline_params(*load("diffuse").desc, cells).empty());
}

}  // namespace
}  // namespace pelage::test
