// `pelage bench noise` end to end on a small scene: the output contract's keys, the
// error falling with the sample count as an unbiased renderer's must (MSE ∝ 1/spp), the
// reference cached and reused, and an animated scene refused with exit 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const char *scene = R"({"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0]},
  "lights": [{"type": "environment", "color": [0.5, 0.6, 0.8]},
             {"type": "distant", "direction": [-1, -1, -1], "angle": 2, "intensity": 3}],
  "objects": [{"mesh": "procedural:icosphere:3", "normals": "smooth",
               "material": {"shader": "diffuse", "params": {"albedo": 0.6},
                            "bsdf": "coated", "roughness": 0.5}}],
  "integrator": {"max_depth": 4}})";

TEST(BenchNoiseCli, ErrorFallsWithSamplesAndTheReferenceIsCached) {
    TempDir tmp;
    const std::string s = tmp.write("s.json", scene), cache = tmp.file("cache");
    const std::string cmd = "bench noise " + s +
                            " --res 48x32 --spp 4 64 --seeds 2 --reference-spp 1024 "
                            "--threads 2 --cache " +
                            cache;
    std::string out, err;
    ASSERT_EQ(run_pelage(cmd, &out, &err), 0) << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    for (const char *key : {"scene", "width", "height", "reference", "object_pixels",
                            "reference_mean", "runs", "by_spp"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_FALSE(j["reference"]["cached"].get<bool>());
    EXPECT_GT(j["object_pixels"].get<double>(), 100);
    ASSERT_EQ(j["runs"].size(), 4u);
    for (const char *key :
         {"spp", "seed", "seconds", "cpu_seconds", "mse", "rmse", "relative_rmse",
          "time_mse", "fireflies", "median_max", "max_error_over_mean"})
        EXPECT_TRUE(j["runs"][0].contains(key)) << key;
    ASSERT_EQ(j["by_spp"].size(), 2u);
    // 16× the samples: at least 8× less MSE (stratified samples do better than 16×).
    const double mse4 = j["by_spp"][0]["mse"], mse64 = j["by_spp"][1]["mse"];
    EXPECT_GT(mse4, 0);
    EXPECT_LT(mse64, mse4 / 8);
    // The second run reads the cached reference and measures the same images.
    std::string out2;
    ASSERT_EQ(run_pelage(cmd, &out2, &err), 0) << err;
    const nlohmann::json j2 = nlohmann::json::parse(out2);
    EXPECT_TRUE(j2["reference"]["cached"].get<bool>());
    EXPECT_EQ(j2["by_spp"][1]["mse"], j["by_spp"][1]["mse"]);
}

// The reference is the scene without its biased settings: a scene that clamps its
// indirect light hard measures darker than its reference, by what the clamp costs.
TEST(BenchNoiseCli, TheReferenceLeavesOutTheBiasedSettings) {
    TempDir tmp;
    // The sphere over a white ground: light bounces between them.
    const char *clamped = R"({"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0]},
  "lights": [{"type": "environment", "color": [0.5, 0.6, 0.8]}],
  "objects": [{"mesh": "procedural:icosphere:3", "normals": "smooth",
               "material": {"shader": "diffuse", "params": {"albedo": 0.8}}},
              {"mesh": "procedural:plane:1x1",
               "transform": {"scale": 20, "translate": [0, -1, 0]},
               "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
  "integrator": {"max_depth": 4, "clamp_indirect": 0.001}})";
    const std::string s = tmp.write("s.json", clamped);
    std::string out, err;
    ASSERT_EQ(run_pelage("bench noise " + s +
                             " --res 48x32 --spp 64 --seeds 1 --reference-spp 256 "
                             "--threads 2 --cache " +
                             tmp.file("cache"),
                         &out, &err),
              0)
        << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    // The clamp removes nearly all light after the first bounce: the ground's light on
    // the sphere, the sphere's on the ground, at least 2 % of the mean, far beyond the
    // noise of 64 spp's mean.
    for (int c = 0; c < 3; ++c)
        EXPECT_LT(j["runs"][0]["mean_rgb"][c].get<double>(),
                  0.98 * j["reference_mean_rgb"][c].get<double>())
            << c;
}

TEST(BenchNoiseCli, AnAnimatedSceneIsExit2) {
    TempDir tmp;
    std::string text = scene;
    text.insert(text.rfind('}'), R"(, "animation": {"frames": 4})");
    std::string out, err;
    EXPECT_EQ(
        run_pelage("bench noise " + tmp.write("a.json", text) + " --res 8x8", &out, &err),
        2);
    EXPECT_NE(err.find("animation"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
