// Analytic scenes for the path tracer: the furnace, a quad light's
// closed-form irradiance, and determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "renderer/denoise/denoise.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

// A flat-shaded icosphere (convex: every bounce escapes) seen whole by the camera.
std::string furnace_scene(float albedo, float L, int spp) {
    return R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 45},
      "film": {"width": 24, "height": 24, "spp": )" +
           std::to_string(spp) + R"(, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": )" +
           std::to_string(L) + R"(}],
      "objects": [{"mesh": "procedural:icosphere:3", "normals": "flat",
                   "material": {"shader": "diffuse", "params": {"albedo": )" +
           std::to_string(albedo) + R"(}}}],
      "integrator": {"max_depth": 16}
    })";
}

// Mean beauty over pixels fully covered by the object (alpha == 1).
double covered_mean(const RenderedImage &img, int *count) {
    double sum = 0;
    *count = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.at(x, y, 3) == 1.0f) {
                sum += (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2)) / 3;
                ++*count;
            }
    return *count ? sum / *count : 0.0;
}

TEST(PathIntegrator, FurnaceDiffuseSphereRendersAlbedoTimesEnvironment) {
    TempDir tmp;
    const float a = 0.5f, L = 2.0f;
    const RenderedImage img = render_json(furnace_scene(a, L, 256), tmp);
    int n = 0;
    const double mean = covered_mean(img, &n);
    ASSERT_GT(n, 100);
    // Convex Lambertian sphere under uniform L: L_o = ∫ (a/π) L cos θ dω = a·L exactly.
    // 1 %: the required tolerance; the Monte Carlo error of the mean is far below it.
    EXPECT_NEAR(mean, a * L, 0.01 * a * L);
    EXPECT_EQ(img.stats.nonfinite_samples, 0u);
}

TEST(PathIntegrator, WhiteFurnaceNonAbsorbingSphereConvergesToEnvironment) {
    TempDir tmp;
    const RenderedImage img = render_json(furnace_scene(1.0f, 1.0f, 256), tmp);
    int n = 0;
    const double mean = covered_mean(img, &n);
    ASSERT_GT(n, 100);
    EXPECT_NEAR(mean, 1.0, 0.01);
}

TEST(PathIntegrator, WhiteFurnaceWithInterreflectionConvergesToEnvironment) {
    TempDir tmp;
    // A non-convex torus: paths bounce between its parts. With albedo 1 under uniform L
    // every surface must render as L, whatever the number of bounces (Russian roulette
    // keeps it unbiased; the depth cap truncates, so it is set far beyond what matters).
    const std::string json = R"({
      "camera": {"position": [0, 2.2, 2.2], "look_at": [0, 0, 0], "fov": 50},
      "film": {"width": 24, "height": 24, "spp": 256, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"mesh": "procedural:torus:48x24", "normals": "flat",
                   "material": {"params": {"albedo": 1}}}],
      "integrator": {"max_depth": 200}
    })";
    const RenderedImage img = render_json(json, tmp);
    int n = 0;
    const double mean = covered_mean(img, &n);
    ASSERT_GT(n, 100);
    EXPECT_NEAR(mean, 1.0, 0.01);
}

TEST(PathIntegrator, UncoveredPixelsSeeTheEnvironmentWithZeroAlpha) {
    TempDir tmp;
    const RenderedImage img = render_json(furnace_scene(0.5f, 2.0f, 4), tmp);
    EXPECT_EQ(img.at(0, 0, 3), 0.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 0), 2.0f);
    EXPECT_EQ(img.at(0, 0, 11), -1.0f);  // id.object: none
}

// Irradiance at p (normal n) from a uniform Lambertian polygon of radiance Le:
// E = Le/2 · Σ_i Θ_i (n · Γ_i), Γ_i = unit(v_i × v_{i+1}), Θ_i the angle between the unit
// vectors v_i, v_{i+1} from p to consecutive corners (Lambert 1760; Arvo 1995,
// "Applications of Irradiance Tensors to the Simulation of Non-Lambertian Phenomena",
// SIGGRAPH, eq. 7).
double polygon_irradiance(const Vec3f *corners, int n, Vec3f p, Vec3f normal, double Le) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3f a = normalize(corners[i] - p),
                    b = normalize(corners[(i + 1) % n] - p);
        const double theta = std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0));
        sum += theta * dot(normal, normalize(cross(a, b)));
    }
    return Le * 0.5 * std::abs(sum);
}

TEST(PathIntegrator, QuadLightOverDiffusePlaneMatchesClosedFormIrradiance) {
    TempDir tmp;
    const float rho = 0.8f, Le = 3.0f, h = 1.0f;
    const int W = 16, H = 16;
    const float cam_y = 0.9f;  // below the light, looking straight down
    const std::string json = R"({
      "camera": {"position": [0, 0.9, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 90},
      "film": {"width": 16, "height": 16, "spp": 8192, "filter": {"type": "box"}},
      "lights": [{"type": "quad", "corner": [-0.5, 1, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                  "intensity": 3}],
      "objects": [{"mesh": "procedural:plane:1x1", "transform": {"scale": 10},
                   "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
      "integrator": {"max_depth": 1}
    })";
    const RenderedImage img = render_json(json, tmp);
    const Vec3f corners[4] = {
        {-0.5f, h, -0.5f}, {0.5f, h, -0.5f}, {0.5f, h, 0.5f}, {-0.5f, h, 0.5f}};
    // Pixel (x, y) covers ground points with X in [-0.9, 0.9] left to right and Z from
    // -0.9 (top) to 0.9 (bottom): fov 90 at height 0.9. Average the closed form over the
    // pixel footprint (8×8 points) rather than taking the centre.
    const float half = cam_y * std::tan(0.5f * pi / 2);
    for (int y : {1, 5, 8, 12, 14})
        for (int x : {2, 7, 10, 15}) {
            double expected = 0;
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    const float sx = (x + (i + 0.5f) / 8) / W,
                                sy = (y + (j + 0.5f) / 8) / H;
                    const Vec3f p{(2 * sx - 1) * half, 0, (2 * sy - 1) * half};
                    expected +=
                        rho / pi * polygon_irradiance(corners, 4, p, {0, 1, 0}, Le) / 64;
                }
            const double got = (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2)) / 3;
            // 2 %: the required tolerance (the Monte Carlo error at 8192 spp is ~0.3 %).
            EXPECT_NEAR(got, expected, 0.02 * expected) << "pixel " << x << "," << y;
        }
}

TEST(PathIntegrator, OneAndTwoThreadsGiveBitIdenticalImages) {
    TempDir tmp;
    const std::string json = R"({
      "camera": {"type": "thin_lens", "position": [0, 1, 4], "look_at": [0, 0, 0], "fov": 35,
                 "aperture_radius": 0.02},
      "film": {"width": 48, "height": 32, "spp": 8},
      "lights": [{"type": "environment", "color": [0.4, 0.5, 0.7]},
                 {"type": "distant", "direction": [-1, -2, -1], "angle": 2, "intensity": 3},
                 {"type": "sphere", "center": [1, 2, 1], "radius": 0.3, "intensity": 5}],
      "objects": [{"mesh": "procedural:sphere:24x24", "normals": "smooth",
                   "material": {"shader": "diffuse", "params": {"albedo": [0.7, 0.4, 0.3]},
                                "bsdf": "coated", "roughness": 0.3}},
                  {"mesh": "procedural:plane:1x1", "transform": {"scale": 10, "translate": [0, -1, 0]}}]
    })";
    const RenderedImage one = render_json(json, tmp, 1, 7);
    const RenderedImage two = render_json(json, tmp, 2, 7);
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_EQ(std::memcmp(one.pixels.data(), two.pixels.data(),
                          one.pixels.size() * sizeof(float)),
              0);
    const RenderedImage other_seed = render_json(json, tmp, 2, 8);
    EXPECT_NE(std::memcmp(one.pixels.data(), other_seed.pixels.data(),
                          one.pixels.size() * sizeof(float)),
              0);
}

TEST(PathIntegrator, ReusedMeshIsInstancedAndRendersLikeCopies) {
    TempDir tmp;
    // The same mesh twice (instanced) must shade as two separate objects with their ids.
    const std::string json = R"({
      "camera": {"position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 32, "height": 16, "spp": 16, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"mesh": "procedural:icosphere:2", "normals": "flat", "transform": {"translate": [-1.2, 0, 0]},
                   "material": {"params": {"albedo": 0.5}}},
                  {"mesh": "procedural:icosphere:2", "normals": "flat", "transform": {"translate": [1.2, 0, 0]},
                   "material": {"params": {"albedo": 0.25}}}]
    })";
    const RenderedImage img = render_json(json, tmp);
    EXPECT_EQ(img.at(11, 8, 11), 0.0f);  // left sphere: object 0
    EXPECT_EQ(img.at(20, 8, 11), 1.0f);  // right sphere: object 1
    EXPECT_NEAR(img.at(11, 8, 0), 0.5f, 0.05f);
    EXPECT_NEAR(img.at(20, 8, 0), 0.25f, 0.03f);
}

TEST(PathIntegrator, PluginAovsReachTheFilmAndNanAlbedosDoNot) {
    TempDir tmp;
    setenv("PELAGE_SHADER_PATH", (std::string(PELAGE_TEST_PLUGIN_DIR) + "/probe").c_str(),
           1);
    const std::string json = R"({
      "camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 45},
      "film": {"width": 24, "height": 24, "spp": 8},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"mesh": "procedural:icosphere:2", "material": {"shader": "aov_probe",
                   "params": {"offset": 3}}}]
    })";
    const renderer::SceneDesc desc = renderer::load_scene_file(tmp.write("s.json", json));
    const renderer::PluginRegistry plugins;
    unsetenv("PELAGE_SHADER_PATH");
    const renderer::Scene scene(desc, plugins);
    ASSERT_EQ(scene.shader_aov_names().size(), 3u);
    EXPECT_EQ(scene.shader_aov_names()[1], "object_plus_offset");
    const renderer::RenderResult r = renderer::render(scene, {});
    const std::vector<float> px = r.film->resolve();
    const int nc = renderer::Film::num_channels;
    int covered = 0;
    for (size_t i = 0; i < px.size() / nc; ++i) {
        const float *p = &px[i * nc];
        // Finite everywhere but depth, which is +inf where nothing was hit.
        for (int c = 0; c < nc; ++c)
            ASSERT_TRUE(std::isfinite(p[c]) || (c == 10 && p[11] < 0 && p[c] > 0))
                << "channel " << c;
        if (p[11] == 0.0f) {  // id.object: the sphere
            ++covered;
            EXPECT_EQ(p[13], p[12]);  // shader.prim == id.primitive (both from sample 0)
            EXPECT_EQ(p[14], 3.0f);   // object 0 + offset 3
        }
    }
    EXPECT_GT(covered, 50);
    EXPECT_EQ(r.stats.nonfinite_samples,
              0u);  // the NaN albedo was clamped to 0 at the hit
}

// A camera hit's footprint is the share of its pixel one sample stands for, at the hit's
// distance, in the object's units: camera_spread_scale(spp) of a pixel's width.
TEST(PathIntegrator, CameraFootprintsAreAPixelsSharePerSample) {
    TempDir tmp;
    setenv("PELAGE_SHADER_PATH", (std::string(PELAGE_TEST_PLUGIN_DIR) + "/probe").c_str(),
           1);
    const renderer::PluginRegistry plugins;
    unsetenv("PELAGE_SHADER_PATH");
    // Straight down from height 2 onto a plane scaled by 10, fov 90 over 16 pixels: at
    // the image centre a pixel is 2 · 2 tan 45° / 16 = 0.25 world units wide, 0.025 in
    // the plane's own units.
    auto centre_footprint = [&](int spp) {
        const std::string json = std::string(R"({
          "camera": {"position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 90},
          "film": {"width": 16, "height": 16, "spp": )") +
                                 std::to_string(spp) + R"(},
          "lights": [{"type": "environment", "color": 1}],
          "objects": [{"mesh": "procedural:plane:1x1", "transform": {"scale": 10},
                       "material": {"shader": "aov_probe"}}]
        })";
        const renderer::SceneDesc desc =
            renderer::load_scene_file(tmp.write(std::to_string(spp) + "spp.json", json));
        const renderer::Scene scene(desc, plugins);
        const std::vector<float> px = renderer::render(scene, {}).film->resolve();
        const int nc = renderer::Film::num_channels;
        double sum = 0;
        for (int y = 7; y <= 8; ++y)
            for (int x = 7; x <= 8; ++x) sum += px[size_t(y * 16 + x) * nc + 15];
        return sum / 4;  // shader.footprint of sample 0, the four centre pixels
    };
    const double one = centre_footprint(1), four = centre_footprint(4),
                 many = centre_footprint(256);
    // Sample 0 lands within 2 pixels of the image centre (its pixel, spread by the
    // filter): off the axis by up to atan(2/8), so up to 1/cos − 1 = 3.1 % farther.
    EXPECT_GE(one, 0.025 * 0.9999);
    EXPECT_LE(one, 0.025 * 1.032);
    EXPECT_NEAR(four / one, 0.5, 0.01);
    EXPECT_NEAR(many / one, 0.125, 0.125 * 0.01);
}

}  // namespace
}  // namespace pelage::test

namespace pelage::test {
namespace {

// Two quad lights over a diffuse plane, one 40× more powerful than the other; the camera
// looks straight down from below both (as in the single-quad test above).
std::string two_quads_scene(const char *selection, int spp) {
    return std::string(R"({
      "camera": {"position": [0, 0.9, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 90},
      "film": {"width": 16, "height": 16, "spp": )") +
           std::to_string(spp) + R"(, "filter": {"type": "box"}},
      "lights": [{"type": "quad", "corner": [-0.6, 1, -0.2], "edge_u": [0.4, 0, 0], "edge_v": [0, 0, 0.4],
                  "intensity": 20},
                 {"type": "quad", "corner": [0.2, 1.2, -0.4], "edge_u": [0.4, 0, 0], "edge_v": [0, 0, 0.8],
                  "intensity": 0.25}],
      "objects": [{"mesh": "procedural:plane:1x1", "transform": {"scale": 10},
                   "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
      "integrator": {"max_depth": 1, "light_selection": ")" +
           selection + R"("}
    })";
}

// Closed-form pixel values of two_quads_scene (pixel footprint averaged, 8×8 points).
std::vector<double> two_quads_expected() {
    const float rho = 0.8f, half = 0.9f;
    const Vec3f a[4] = {
        {-0.6f, 1, -0.2f}, {-0.2f, 1, -0.2f}, {-0.2f, 1, 0.2f}, {-0.6f, 1, 0.2f}};
    const Vec3f b[4] = {
        {0.2f, 1.2f, -0.4f}, {0.6f, 1.2f, -0.4f}, {0.6f, 1.2f, 0.4f}, {0.2f, 1.2f, 0.4f}};
    std::vector<double> e(16 * 16, 0.0);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    const float sx = (x + (i + 0.5f) / 8) / 16,
                                sy = (y + (j + 0.5f) / 8) / 16;
                    const Vec3f p{(2 * sx - 1) * half, 0, (2 * sy - 1) * half};
                    e[y * 16 + x] += rho / pi / 64 *
                                     (polygon_irradiance(a, 4, p, {0, 1, 0}, 20) +
                                      polygon_irradiance(b, 4, p, {0, 1, 0}, 0.25));
                }
    return e;
}

double relative_rms_error(const RenderedImage &img, const std::vector<double> &expected) {
    double se = 0, s2 = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const double got = (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2)) / 3;
            se += (got - expected[y * 16 + x]) * (got - expected[y * 16 + x]);
            s2 += expected[y * 16 + x] * expected[y * 16 + x];
        }
    return std::sqrt(se / s2);
}

TEST(PathIntegrator, LightsAreSelectedInProportionToTheirPower) {
    TempDir tmp;
    const renderer::SceneDesc desc =
        renderer::load_scene_file(tmp.write("s.json", two_quads_scene("power", 1)));
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    const renderer::Lights &l = scene.lights();
    // Quads: Φ = π A L; 0.16 · 20 against 0.32 · 0.25.
    EXPECT_NEAR(l.select_pdf(0) / l.select_pdf(1), (0.16 * 20) / (0.32 * 0.25), 1e-3);
    EXPECT_NEAR(l.select_pdf(0) + l.select_pdf(1), 1.0, 1e-6);
    // select() over evenly spaced u picks each light with its select_pdf (alias table).
    constexpr int n = 1 << 16;
    int picked[2] = {0, 0};
    for (int k = 0; k < n; ++k) {
        float pdf;
        const int i = l.select((k + 0.5f) / n, &pdf);
        ASSERT_TRUE(i == 0 || i == 1);
        EXPECT_EQ(pdf, l.select_pdf(i));
        ++picked[i];
    }
    EXPECT_NEAR(double(picked[1]) / n, l.select_pdf(1), 2.0 / n);
}

TEST(PathIntegrator, LightSelectionsConvergeToTheSameImageSamplingAllWithLeastNoise) {
    TempDir tmp;
    const std::vector<double> expected = two_quads_expected();
    // Same expectation: at 4096 spp both selections match the closed form within 1 % in
    // the mean over each half of the image (each light dominates one half; a half-image
    // mean keeps the noise of uniform selection near 0.2 %).
    for (const char *sel : {"all", "power", "uniform"}) {
        const RenderedImage img = render_json(two_quads_scene(sel, 4096), tmp);
        for (int half = 0; half < 2; ++half) {
            double got = 0, want = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 8 * half; x < 8 * half + 8; ++x) {
                    got += (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2)) / 3;
                    want += expected[y * 16 + x];
                }
            EXPECT_NEAR(got, want, 0.01 * want) << sel << " half " << half;
        }
    }
    // Less noise: at 16 spp the image error is Monte Carlo noise; choosing the bright
    // light 40× more often than the dim one must lower it (to about 0.22× the error of
    // uniform selection here; 0.8 leaves room for the noise of the noise estimate).
    const double e_power = relative_rms_error(
                     render_json(two_quads_scene("power", 16), tmp), expected),
                 e_uniform = relative_rms_error(
                     render_json(two_quads_scene("uniform", 16), tmp), expected);
    // Sampling both lights at every vertex removes the choice's variance altogether.
    const double e_all =
        relative_rms_error(render_json(two_quads_scene("all", 16), tmp), expected);
    std::printf("relative RMS error at 16 spp: all %.4f, power %.4f, uniform %.4f\n",
                e_all, e_power, e_uniform);
    EXPECT_LT(e_power, 0.8 * e_uniform);
    EXPECT_LT(e_all, 0.8 * e_power);
}

TEST(PathIntegrator, AreaLightsOccludeAndTheirBackIsBlack) {
    TempDir tmp;
    // Sun straight down onto a plane; a quad light facing up (away from the plane) hangs
    // between them: its shadow is black (it emits nothing downwards), elsewhere the plane
    // shows ρE/π. Seen from above, a one-sided quad facing down shows its black back.
    const std::string below = R"({
      "camera": {"position": [0, 0.5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 90},
      "film": {"width": 16, "height": 16, "spp": 1024, "filter": {"type": "box", "radius": 0.5}},
      "lights": [{"type": "distant", "direction": [0, -1, 0], "intensity": 3},
                 {"type": "quad", "corner": [-0.1, 1, -0.1], "edge_u": [0, 0, 0.2], "edge_v": [0.2, 0, 0],
                  "intensity": 50}],
      "objects": [{"mesh": "procedural:plane:1x1", "transform": {"scale": 10},
                   "material": {"shader": "diffuse", "params": {"albedo": 0.5}}}],
      "integrator": {"max_depth": 1}
    })";
    const RenderedImage img = render_json(below, tmp);
    EXPECT_EQ(img.at(8, 8, 0), 0.0f);  // in the quad's shadow
    // 2 %: the sun is picked for ~99 % of the samples (by power), so the estimate is
    // noisy at the 0.4 % level.
    EXPECT_NEAR(img.at(0, 0, 0), 0.5f * 3 / pi, 0.02 * 0.5f * 3 / pi);
    const std::string above = R"({
      "camera": {"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 20},
      "film": {"width": 16, "height": 16, "spp": 4, "filter": {"type": "box"}},
      "lights": [{"type": "quad", "corner": [-1, 1, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2],
                  "intensity": 50}],
      "objects": [{"mesh": "procedural:plane:1x1", "transform": {"translate": [0, -5, 0]}}]
    })";
    const RenderedImage back = render_json(above, tmp);
    EXPECT_EQ(back.at(8, 8, 0), 0.0f);
    EXPECT_EQ(back.at(8, 8, 3), 1.0f);  // but it is there: alpha 1
}

}  // namespace
}  // namespace pelage::test

namespace pelage::test {
namespace {

// clamp_indirect leaves direct light alone and caps the rest: clamped to almost nothing,
// a 4-bounce render is the direct-only render (sun and sky at the first hit); unclamped
// it is brighter (light between the sphere and the ground).
TEST(PathIntegrator, ClampIndirectCapsAllButDirectLight) {
    TempDir tmp;
    auto scene = [](int depth, const char *clamp) {
        return std::string(R"({"camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
          "film": {"width": 24, "height": 24, "spp": 16},
          "lights": [{"type": "environment", "color": [0.5, 0.6, 0.8]},
                     {"type": "distant", "direction": [-1, -1, -1], "intensity": 3}],
          "objects": [{"mesh": "procedural:icosphere:2",
                       "material": {"shader": "diffuse", "params": {"albedo": 0.8}}},
                      {"mesh": "procedural:plane:1x1",
                       "transform": {"scale": 10, "translate": [0, -1, 0]},
                       "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
          "integrator": {"max_depth": )") +
               std::to_string(depth) + R"(, "clamp_indirect": )" + clamp + "}}";
    };
    const RenderedImage direct = render_json(scene(1, "0"), tmp);
    const RenderedImage clamped = render_json(scene(4, "1e-9"), tmp);
    const RenderedImage full = render_json(scene(4, "0"), tmp);
    double d = 0, c = 0, f = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            d += direct.at(x, y, 1);
            c += clamped.at(x, y, 1);
            f += full.at(x, y, 1);
            EXPECT_NEAR(clamped.at(x, y, 1), direct.at(x, y, 1), 1e-5);
        }
    EXPECT_GT(f, 1.05 * c);
}

// The denoiser's half buffers hold, apart, what the first hit's light samples
// gathered: with no bounce that is the whole beauty; with bounces, the bounces are
// the rest.
TEST(PathIntegrator, TheHalvesHoldTheFirstHitsLightSamplesApart) {
    TempDir tmp;
    auto halves = [&](int depth) {
        const std::string path = tmp.write("s.json", R"({
          "camera": {"position": [0, 1, 4], "look_at": [0, 0, 0]},
          "film": {"width": 20, "height": 20, "spp": 8, "denoise": true},
          "lights": [{"type": "distant", "direction": [-1, -1, -1], "intensity": 3}],
          "objects": [{"mesh": "procedural:icosphere:2",
                       "material": {"shader": "diffuse", "params": {"albedo": 0.8}}},
                      {"mesh": "procedural:plane:1x1",
                       "transform": {"scale": 10, "translate": [0, -1, 0]},
                       "material": {"shader": "diffuse", "params": {"albedo": 0.8}}}],
          "integrator": {"max_depth": )" + std::to_string(depth) +
                                                         "}}");
        const renderer::SceneDesc desc = renderer::load_scene_file(path);
        const renderer::PluginRegistry plugins;
        const renderer::Scene scene(desc, plugins);
        return renderer::render(scene, renderer::RenderOptions{}).film->resolve_halves();
    };
    const renderer::DenoiseInput one = halves(1);
    double lit = 0;
    for (const renderer::DenoiseHalf &h : one.half) {
        ASSERT_EQ(h.direct.size(), h.colour.size());
        for (size_t i = 0; i < h.colour.size(); ++i) {
            EXPECT_FLOAT_EQ(h.direct[i], h.colour[i]) << i;
            lit += h.colour[i];
        }
    }
    EXPECT_GT(lit, 100);  // the sun lights the sphere and the ground
    const renderer::DenoiseInput four = halves(4);
    double direct = 0, rest = 0;
    for (const renderer::DenoiseHalf &h : four.half)
        for (size_t i = 0; i < h.colour.size(); ++i) {
            EXPECT_LE(h.direct[i], h.colour[i] * (1 + 1e-6f)) << i;
            direct += h.direct[i];
            rest += h.colour[i] - h.direct[i];
        }
    // The same first-hit light samples (the sampler's numbers for the first vertex do
    // not depend on the depth), and the bounces on top.
    EXPECT_NEAR(direct, lit, 1e-3 * lit);
    EXPECT_GT(rest, 0.05 * direct);
}

}  // namespace
}  // namespace pelage::test
