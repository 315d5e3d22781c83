// The lat-long environment: its sampling density is a density, agrees with pdf(), and a
// constant image behaves like a constant environment in the furnace.
#include "renderer/lights/light_environment.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "renderer/core/sampler.h"
#include "renderer/core/sampling.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

// A 32×16 map: dim sky, one bright 2×2 "sun" block, a warm band near the horizon.
std::string write_env(const TempDir &dir, bool constant) {
    const int W = 32, H = 16;
    std::vector<float> px(size_t(W) * H * 3);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float *p = &px[(size_t(y) * W + x) * 3];
            p[0] = p[1] = p[2] = constant ? 1.5f : 0.2f;
            if (!constant && y >= 3 && y <= 4 && x >= 10 && x <= 11)
                p[0] = p[1] = p[2] = 50.0f;
            if (!constant && y == 8) {
                p[0] = 1.0f;
                p[1] = 0.5f;
            }
        }
    const std::string path = dir.file(constant ? "const.exr" : "sky.exr");
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(W, H, 3, OIIO::TypeDesc::FLOAT);
    out->open(path, spec);
    out->write_image(OIIO::TypeDesc::FLOAT, px.data());
    out->close();
    return path;
}

TEST(EnvironmentLight, PdfIntegratesToOneAndMatchesSample) {
    TempDir tmp;
    const EnvironmentLight env(write_env(tmp, false), 1.0f, 30.0f);
    Sampler s(5, 0);
    // ∫ pdf dω by uniform sphere sampling: E[pdf / (1/4π)] = 1.
    double integral = 0;
    constexpr int n = 400000;
    for (int i = 0; i < n; ++i) {
        s.start_pixel_sample(uint32_t(i), 1, 0);
        const float u1 = s.get_1d(), u2 = s.get_1d();
        integral += env.pdf(sample_uniform_sphere(u1, u2)) * 4 * pi;
    }
    // 2 %: the bright block makes the uniform estimate noisy.
    EXPECT_NEAR(integral / n, 1.0, 0.02);
    int bright = 0;
    for (int i = 0; i < 2000; ++i) {
        s.start_pixel_sample(uint32_t(i), 2, 0);
        const float u1 = s.get_1d(), u2 = s.get_1d();
        Vec3f d;
        float pdf;
        const Rgb L = env.sample(u1, u2, &d, &pdf);
        ASSERT_GT(pdf, 0);
        EXPECT_NEAR(pdf, env.pdf(d), 1e-3f * pdf + 1e-6f);
        EXPECT_EQ(L, env.eval(d));
        bright += L.x > 10;
    }
    EXPECT_GT(bright, 1000);  // importance sampling goes where the light is
}

TEST(EnvironmentLight, ConstantImageFurnaceRendersAlbedoTimesRadiance) {
    TempDir tmp;
    const std::string img = write_env(tmp, true);
    const RenderedImage r = render_json(R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 45},
      "film": {"width": 16, "height": 16, "spp": 256, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "image": ")" +
                                            img + R"(", "intensity": 2}],
      "objects": [{"mesh": "procedural:icosphere:3", "normals": "flat",
                   "material": {"params": {"albedo": 0.5}}}]
    })",
                                        tmp);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            if (r.at(x, y, 3) == 1.0f) {
                sum += r.at(x, y, 1);
                ++n;
            }
    ASSERT_GT(n, 30);
    EXPECT_NEAR(sum / n, 0.5 * 1.5 * 2, 0.01 * 1.5);  // a · L within 1 %
}

TEST(PathIntegrator, CancelledRenderStopsAndReportsNoCompletedPass) {
    TempDir tmp;
    const std::string path = tmp.write(
        "s.json", R"({"camera": {}, "film": {"width": 8, "height": 8, "spp": 64},
        "objects": [{"mesh": "procedural:icosphere:1"}]})");
    const renderer::SceneDesc desc = renderer::load_scene_file(path);
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    std::atomic<bool> cancel{true};
    renderer::RenderOptions o;
    o.cancel = &cancel;
    const renderer::RenderResult r = renderer::render(scene, o);
    EXPECT_TRUE(r.interrupted);
    EXPECT_EQ(r.spp_done, 0);
}

}  // namespace
}  // namespace pelage::test
