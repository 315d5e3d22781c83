// Progress counts work, not steps: a schedule of doubling passes shows the fraction of
// samples taken and an ETA from it; a render accounts for every pixel-sample of its
// budget (adaptive sampling included); and building a scene names its set-up steps.
#include "renderer/core/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "renderer/integrator/render.h"
#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

TEST(Progress, DoublingPassesAdvanceByTheirSamples) {
    // The renderer's schedule for 16 spp over 100 pixels: passes of 1, 1, 2, 4, 8.
    const uint64_t pixels = 100;
    Progress p("render", pixels * 16, false);
    const int bounds[] = {0, 1, 2, 4, 8, 16};
    for (int pass = 0; pass < 5; ++pass) {
        p.advance(pixels * uint64_t(bounds[pass + 1] - bounds[pass]));
        EXPECT_DOUBLE_EQ(p.fraction(), bounds[pass + 1] / 16.0) << "pass " << pass;
    }
    EXPECT_EQ(p.done(), p.total());
    // Three of five passes are a quarter of the work, not 60 %.
    Progress q("render", pixels * 16, false);
    q.advance(pixels * 4);
    EXPECT_DOUBLE_EQ(q.fraction(), 0.25);
}

TEST(Progress, LineShowsTheFractionAndAnEtaFromIt) {
    // A quarter done in 10 s: 30 s to go.
    const std::string quarter = Progress::line("render", 0.25, 10.0);
    EXPECT_NE(quarter.find("render [#######                       ]  25%  ETA 30 s"),
              std::string::npos)
        << quarter;
    const std::string done = Progress::line("render", 1.0, 12.34);
    EXPECT_NE(done.find("100%  12.3 s"), std::string::npos) << done;
    EXPECT_EQ(done.find("ETA"), std::string::npos) << done;
    EXPECT_EQ(SetupPhase::line("render", "growing fur", 3.44),
              "render: growing fur ...  3.4 s");
}

RenderResult render_text(const TempDir &tmp, const std::string &film) {
    const std::string path = tmp.write("scene.json", R"({
      "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 30},
      "film": )" + film + R"(,
      "lights": [{"type": "environment", "color": [0.4, 0.5, 0.7]},
                 {"type": "distant", "direction": [-1, -1, -1], "angle": 2, "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:3",
                   "material": {"shader": "diffuse", "params": {"albedo": 0.6}}}],
      "integrator": {"max_depth": 3}})");
    const SceneDesc desc = load_scene_file(path);
    const PluginRegistry plugins;
    const Scene scene(desc, plugins);
    return render(scene, RenderOptions{});
}

TEST(Progress, RenderCountsEveryPixelSampleOfItsBudget) {
    TempDir tmp;
    // 24 × 20 pixels (tiles cut at the edges), 48 spp: passes 1, 1, 2, 4, 8, 16, 16.
    const RenderResult full =
        render_text(tmp, R"({"width": 24, "height": 20, "spp": 48})");
    EXPECT_EQ(full.work_total, uint64_t(24 * 20 * 48));
    EXPECT_EQ(full.work_done, full.work_total);
    EXPECT_EQ(full.stats.samples, full.work_total);  // the independent count
    // Adaptive: the sky stops at min_spp; its unneeded samples are counted done, so the
    // bar ends at 100 % with fewer samples taken.
    const RenderResult adaptive = render_text(
        tmp,
        R"({"width": 24, "height": 20, "spp": 256, "noise_threshold": 0.01, "min_spp": 8})");
    EXPECT_EQ(adaptive.work_total, uint64_t(24 * 20 * 256));
    EXPECT_EQ(adaptive.work_done, adaptive.work_total);
    EXPECT_LT(adaptive.stats.samples, adaptive.work_total / 2);
}

TEST(SetupPhase, BuildingAFurrySceneNamesItsSteps) {
    TempDir tmp;
    const std::string path = tmp.write("scene.json", R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 42},
      "film": {"width": 8, "height": 8, "spp": 1},
      "lights": [{"type": "environment", "color": [0.5, 0.6, 0.8]}],
      "objects": [{"mesh": "procedural:sphere:16x16",
                   "material": {"shader": "diffuse", "params": {"albedo": 0.5}},
                   "fur": {"density": 300, "length": 0.1}}]})");
    const SceneDesc desc = load_scene_file(path);
    const PluginRegistry plugins;
    std::vector<std::string> seen;
    SetupPhase::observe([&](const std::string &name) { seen.push_back(name); });
    { const Scene scene(desc, plugins); }
    SetupPhase::observe(nullptr);
    const std::vector<std::string> expected = {"loading meshes", "building the BVH",
                                               "setting up shaders", "growing fur",
                                               "building the BVH with the fur"};
    EXPECT_EQ(seen, expected);
}

TEST(SetupPhase, NestedPhasesDrawAndClearWithoutHanging) {
    // Drawn to stderr as on a terminal: the ticker starts with the first phase and stops
    // with the last, however they nest.
    SetupPhase::show("test", true);
    for (int round = 0; round < 3; ++round) {
        const SetupPhase outer("outer");
        { const SetupPhase inner("inner"); }
        { const SetupPhase inner("inner again"); }
    }
    SetupPhase::show("", false);
}

}  // namespace
}  // namespace pelage::test
