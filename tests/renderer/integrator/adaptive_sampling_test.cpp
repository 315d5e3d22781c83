// Adaptive sampling (film.noise_threshold): pixels that cannot be noisy stop at min_spp,
// noisy ones go on, the noise estimate is the standard error the samples say, and the
// result is the same at any thread count.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/image/film.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

// A diffuse sphere lit by a sun and seen against a constant sky: sky pixels have no
// variance at all, lit sphere pixels do (antialiased edges, the sky through the BSDF).
std::string scene(double threshold, int spp) {
    return R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 30},
      "film": {"width": 32, "height": 32, "spp": )" +
           std::to_string(spp) + R"(, "noise_threshold": )" + std::to_string(threshold) +
           R"(, "min_spp": 8},
      "lights": [{"type": "environment", "color": [0.4, 0.5, 0.7]},
                 {"type": "distant", "direction": [-1, -1, -1], "angle": 2, "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:3",
                   "material": {"shader": "diffuse", "params": {"albedo": 0.6}}}],
      "integrator": {"max_depth": 3}})";
}

TEST(AdaptiveSampling, QuietPixelsStopAndNoisyOnesGoOn) {
    TempDir tmp;
    const RenderedImage full = render_json(scene(0, 256), tmp);
    const RenderedImage adaptive = render_json(scene(0.01, 256), tmp);
    EXPECT_EQ(full.stats.samples, uint64_t(32 * 32 * 256));
    // The sky stops at 8 samples; the sphere (about a quarter of the image) and its
    // neighbours go on: fewer samples than half of the full render's, more than the
    // minimum everywhere.
    EXPECT_LT(adaptive.stats.samples, full.stats.samples / 2);
    EXPECT_GT(adaptive.stats.samples, uint64_t(32 * 32 * 8 * 2));
    // The sky is exact either way; the image stays close to the full render's.
    EXPECT_NEAR(adaptive.at(0, 0, 0), full.at(0, 0, 0), 1e-5);
    double err = 0, sum = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            err += std::abs(adaptive.at(x, y, 1) - full.at(x, y, 1));
            sum += full.at(x, y, 1);
        }
    EXPECT_LT(err / sum, 0.02);
    // A looser threshold stops sooner; the same threshold at 1 and 2 threads is the same
    // image.
    EXPECT_LT(render_json(scene(0.05, 256), tmp).stats.samples, adaptive.stats.samples);
    EXPECT_EQ(render_json(scene(0.01, 256), tmp, 1).pixels,
              render_json(scene(0.01, 256), tmp, 2).pixels);
}

TEST(AdaptiveSampling, FilmNoiseIsTheStandardErrorOverTheRootOfTheLevel) {
    renderer::Film film(1, 1);
    EXPECT_TRUE(std::isinf(film.noise(0, 0)));
    // Grey samples 0.2 and 0.6: mean 0.4, sample variance 0.08, standard error 0.2.
    for (float v : {0.2f, 0.6f}) {
        renderer::FilmSample s;
        s.L = {v, v, v};
        film.add(0, 0, 1.0f, s);
    }
    EXPECT_NEAR(film.noise(0, 0), 0.2 / std::sqrt(0.4), 1e-5);
}

}  // namespace
}  // namespace pelage::test
