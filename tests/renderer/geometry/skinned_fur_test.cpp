// A coat on a skin that a clip poses is counted on the skin's default pose, the shape a
// viewer shows (glTF 2.0 §3.7.3), whatever space the file's vertices are read in: the
// armature tube is laid out as Blender exports a Mixamo character, its vertices read at
// 1/100 of that shape under the armature's scale.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "renderer/scene_frame/scene_frame.h"
#include "tests/renderer/animation/armature_tube.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using nlohmann::json;

constexpr int around = 24, along = 16;
constexpr double density = 2000;

std::string tube_scene(const TempDir &tmp, const std::string &name, bool clip) {
    json object = {{"name", "tube"},
                   {"mesh", tmp.file("tube.gltf")},
                   {"material", {{"shader", "diffuse"}}},
                   {"fur",
                    {{"density", density},
                     {"length", 0.05},
                     {"root_radius", 0.001},
                     {"tip_radius", 0.0003},
                     {"segments", 4},
                     {"seed", 3}}}};
    json scene = {{"camera", {{"position", {0, 1, 5}}, {"look_at", {0, 0.75, 0}}}},
                  {"film", {{"width", 16}, {"height", 16}, {"spp", 1}}},
                  {"lights", {{{"type", "environment"}}}}};
    if (clip) {
        object["animation"] = {{"clip", "Sway"}};
        scene["animation"] = {{"frames", 12}, {"fps", 24}};
    }
    scene["objects"] = {object};
    return tmp.write(name, scene.dump());
}

size_t strands(const renderer::SceneDesc &desc) {
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    return scene.fur() ? scene.fur()->num_strands() : 0;
}

TEST(SkinnedFur, AClipsCoatIsCountedOnTheSkinsDefaultPose) {
    TempDir tmp;
    tmp.write("tube.gltf", armature_tube(around, along));
    // The expected count: density × the default pose's side area (a 24-gon prism of
    // radius r, height h), Poisson-distributed around it.
    const double r = armature_tube_radius, h = armature_tube_height;
    const double area = 2 * around * r * std::sin(M_PI / around) * h;
    const double expected = density * area, spread = 5 * std::sqrt(expected);

    const renderer::SceneDesc still =
        renderer::load_scene_file(tube_scene(tmp, "still.json", false));
    EXPECT_NEAR(double(strands(still)), expected, spread) << "the still (default pose)";

    const renderer::SceneDesc clip =
        renderer::load_scene_file(tube_scene(tmp, "clip.json", true));
    const size_t at0 = strands(renderer::scene_at_frame(clip, 0));
    EXPECT_NEAR(double(at0), expected, spread) << "the clip's first frame";
    // The same roots in every pose.
    EXPECT_EQ(strands(renderer::scene_at_frame(clip, 8)), at0);
}

}  // namespace
}  // namespace pelage::test
