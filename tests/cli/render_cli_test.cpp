// `pelage render`, `pelage shaders` end to end: the --stats-json output contract, the
// EXR from the CLI, bit-identical output at 1 and 2 threads, plugin refusal.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const char *small_scene = R"({
  "camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "fov": 40},
  "film": {"width": 40, "height": 30, "spp": 4},
  "lights": [{"type": "environment", "color": [0.5, 0.6, 0.8]},
             {"type": "distant", "direction": [-1, -1, -0.5], "angle": 1, "intensity": 2}],
  "objects": [{"mesh": "procedural:sphere:16x16", "normals": "smooth",
               "material": {"shader": "diffuse", "params": {"albedo": [0.8, 0.3, 0.2]}, "bsdf": "coated"}},
              {"mesh": "procedural:plane:1x1", "transform": {"scale": 5, "translate": [0, -1, 0]}}]
})";

std::vector<float> read_pixels(const std::string &path,
                               std::vector<std::string> *names = nullptr) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> px(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    if (names) names->assign(s.channelnames.begin(), s.channelnames.end());
    return px;
}

TEST(RenderCli, StatsJsonHasTheContractKeys) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", small_scene);
    ASSERT_EQ(run_pelage("render " + scene + " -o " + tmp.file("o.exr") +
                         " --spp 2 --res 20x10 --stats-json " + tmp.file("st.json") +
                         " --preview " + tmp.file("p.png")),
              0);
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("st.json")));
    for (const char *k : {"seconds", "spp", "width", "height", "rays", "rays_per_second",
                          "plugin_seconds"})
        EXPECT_TRUE(s.contains(k)) << k;
    EXPECT_EQ(s["spp"], 2);
    EXPECT_EQ(s["width"], 20);
    EXPECT_EQ(s["height"], 10);
    EXPECT_GE(s["rays"].get<double>(), 20 * 10 * 2);
    EXPECT_TRUE(std::filesystem::exists(tmp.file("p.png")));
    std::vector<std::string> names;
    // Beauty, albedo, N, depth, two ids: the diffuse plugin names no shader slot.
    EXPECT_EQ(read_pixels(tmp.file("o.exr"), &names).size(), 20u * 10 * 13);
}

TEST(RenderCli, OneAndTwoThreadsGiveBitIdenticalExrs) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", small_scene);
    ASSERT_EQ(run_pelage("render " + scene + " -q --threads 1 --sampler-seed 3 -o " +
                         tmp.file("a.exr")),
              0);
    ASSERT_EQ(run_pelage("render " + scene + " -q --threads 2 --sampler-seed 3 -o " +
                         tmp.file("b.exr")),
              0);
    const auto a = read_pixels(tmp.file("a.exr")), b = read_pixels(tmp.file("b.exr"));
    ASSERT_FALSE(a.empty());
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

TEST(RenderCli, NoOutputIsExit2NamingTheField) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", small_scene);
    std::string err;
    EXPECT_EQ(run_pelage("render " + scene, nullptr, &err), 2);
    EXPECT_NE(err.find("film.output"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("render " + scene + " -o x.exr --res 10by10", nullptr, &err), 2);
    EXPECT_NE(err.find("--res"), std::string::npos) << err;
    EXPECT_EQ(
        run_pelage("render " + scene + " -o " + tmp.file("nope/x.exr"), nullptr, &err),
        2);
    EXPECT_NE(err.find("nope"), std::string::npos) << err;
}

TEST(RenderCli, InterruptWritesTheCompletedPassesAtomically) {
    TempDir tmp;
    // Far more samples than can finish: Ctrl-C (SIGINT, sent by timeout) must
    // stop the render and still write a whole image, marked as interrupted. (The
    // image holds the passes completed: at least one must finish before the signal.)
    const std::string scene =
        tmp.write("s.json", R"({"camera": {}, "film": {"width": 32, "height": 32,
        "spp": 1000000}, "lights": [{"type": "environment"}], "objects": [{"mesh": "procedural:icosphere:2"}]})");
    const std::string cmd = interrupt_after() + std::string(PELAGE_BINARY) + " render " +
                            scene + " -q -o " + tmp.file("o.exr") + " --stats-json " +
                            tmp.file("s.json") + " 2>" + tmp.file("err");
    const int rc = std::system(cmd.c_str());
    EXPECT_EQ(WEXITSTATUS(rc), 130);  // 128 + SIGINT, the shell convention
    auto in = OIIO::ImageInput::open(tmp.file("o.exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_int_attribute("pelage:interrupted"), 1);
    EXPECT_GE(in->spec().get_int_attribute("pelage:spp"), 1);
    // Complete and valid: every pixel of every channel reads back, and the lit
    // sphere (default environment, radiance 1) covers the centre with non-zero beauty.
    const OIIO::ImageSpec &spec = in->spec();
    ASSERT_EQ(spec.width, 32);
    std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
    ASSERT_TRUE(
        in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    // (Depth is +inf where nothing was hit: finite or inf, never NaN.)
    const int depth = spec.channelindex("depth.Z");
    for (size_t i = 0; i < px.size(); ++i)
        ASSERT_TRUE(std::isfinite(px[i]) ||
                    (int(i % spec.nchannels) == depth && px[i] > 0));
    const float *centre = &px[(size_t(16) * spec.width + 16) * spec.nchannels];
    EXPECT_GT(centre[0], 0.0f);
    EXPECT_EQ(centre[3], 1.0f);  // alpha: covered
    const auto st = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    EXPECT_TRUE(st["interrupted"].get<bool>());
    // Only the final files remain: no temporaries.
    size_t files = 0;
    for (const auto &e : std::filesystem::directory_iterator(tmp.path()))
        files += e.path().filename().string()[0] == '.';
    EXPECT_EQ(files, 0u);
}

// The EXR says when fur was rendered with path regularisation (biased, as firefly
// clamping is), and with what value; a bare scene, or regularisation off, says nothing.
TEST(RenderCli, TheExrRecordsFurPathRegularisation) {
    TempDir tmp;
    const auto scene = [&](const std::string &fur, const std::string &integrator) {
        return tmp.write("s.json", R"({
      "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
      "film": {"width": 12, "height": 12, "spp": 1},
      "integrator": {)" + integrator + R"(},
      "lights": [{"type": "environment"}],
      "objects": [{"mesh": "procedural:icosphere:2")" +
                                       fur + "}]}");
    };
    const std::string fur =
        R"(, "fur": {"density": 200, "length": 0.1, "root_radius": 0.005})";
    const auto attribute = [&](const std::string &s) {
        EXPECT_EQ(run_pelage("render " + s + " -q -o " + tmp.file("o.exr")), 0);
        auto in = OIIO::ImageInput::open(tmp.file("o.exr"));
        return in ? in->spec().get_float_attribute("pelage:fur_bounce_roughness", -1)
                  : -2.0f;
    };
    EXPECT_FLOAT_EQ(attribute(scene(fur, "")), 0.4f);  // the default
    EXPECT_FLOAT_EQ(attribute(scene(fur, R"("fur_bounce_roughness": 0.7)")), 0.7f);
    EXPECT_EQ(attribute(scene(fur, R"("fur_bounce_roughness": 0)")), -1.0f);
    EXPECT_EQ(attribute(scene("", "")), -1.0f);
}

TEST(ShadersCli, ListsDiffuseAndItsParameters) {
    std::string out;
    ASSERT_EQ(run_pelage("shaders --json", &out), 0);
    const auto j = nlohmann::json::parse(out);
    bool found = false;
    for (const auto &s : j["shaders"])
        if (s["name"] == "diffuse") {
            found = true;
            EXPECT_EQ(s["params"][0]["name"], "albedo");
            EXPECT_EQ(s["params"][0]["type"], "rgb");
        }
    EXPECT_TRUE(found) << out;
    std::string err;
    EXPECT_EQ(run_pelage("shaders wroley", nullptr, &err), 2);
    EXPECT_NE(err.find("wroley"), std::string::npos);
}

// Renders an icosphere with the test plugin `shader` (tests/data/plugins): the exit
// status and stderr; `written` says whether the EXR appeared.
int render_with_test_plugin(const std::string &shader, std::string *err, bool *written) {
    TempDir tmp;
    const std::string scene = tmp.write(
        "s.json", R"({"camera": {}, "objects": [{"mesh": "procedural:icosphere:1",
            "material": {"shader": ")" +
                      shader + R"("}}]})");
    const std::string env =
        "PELAGE_SHADER_PATH=" + std::string(PELAGE_TEST_PLUGIN_DIR) + " ";
    const int rc = std::system((env + PELAGE_BINARY + " render " + scene + " -o " +
                                tmp.file("o.exr") + " 2>" + tmp.file("err"))
                                   .c_str());
    std::ifstream in(tmp.file("err"));
    err->assign(std::istreambuf_iterator<char>(in), {});
    *written = std::filesystem::exists(tmp.file("o.exr"));
    return WEXITSTATUS(rc);
}

TEST(ShadersCli, WrongAbiPluginIsRefusedNamingTheFile) {
    std::string err;
    bool written = true;
    EXPECT_NE(render_with_test_plugin("bad_abi", &err, &written), 0);
    EXPECT_NE(err.find("bad_abi.so"), std::string::npos) << err;
    EXPECT_NE(err.find("ABI version 999"), std::string::npos) << err;
    EXPECT_FALSE(written);
}

TEST(ShadersCli, AnAbi2PluginIsRefusedAskingForARebuild) {
    std::string err;
    bool written = true;
    EXPECT_NE(render_with_test_plugin("old_abi", &err, &written), 0);
    EXPECT_NE(err.find("old_abi.so: shader plugin ABI version 2, this pelage needs 3 "
                       "(rebuild the plugin"),
              std::string::npos)
        << err;
    EXPECT_FALSE(written);
}

}  // namespace
}  // namespace pelage::test
