// `pelage render --denoise` and `pelage look --denoise` end to end: the EXR keeps the
// noisy beauty byte for byte and adds the denoised layer, which is closer to a converged
// render of the same scene than the noisy one; Cryptomatte is never denoised; the
// preview shows the denoised image; the same bytes at any thread count; one sample per
// pixel is kept noisy with a warning. The denoiser's own properties (analytic images,
// edges, garbage statistics) are tests/renderer/denoise; tiles are FarmCli's.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

struct Exr {
    int width = 0, height = 0;
    std::vector<std::string> names;
    std::vector<float> pixels;
    std::vector<float> channel(const std::string &name) const {
        std::vector<float> out;
        for (size_t c = 0; c < names.size(); ++c)
            if (names[c] == name) {
                for (size_t i = 0; i < size_t(width) * height; ++i)
                    out.push_back(pixels[i * names.size() + c]);
            }
        return out;
    }
};

Exr read_exr(const std::string &path) {
    Exr e;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return e;
    const OIIO::ImageSpec &s = in->spec();
    e.width = s.width;
    e.height = s.height;
    e.names = s.channelnames;
    e.pixels.resize(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, e.pixels.data());
    return e;
}

std::vector<unsigned char> read_png(const std::string &path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<unsigned char> px(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::UINT8, px.data());
    return px;
}

// A grey ball lit by a small sphere light over a ground plane: soft shadows and a
// penumbra, the noise a denoiser is for.
std::string lit_scene(int spp, const std::string &film_extra = "") {
    return R"({"camera": {"position": [0, 1.2, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 64, "height": 48, "spp": )" +
           std::to_string(spp) + film_extra + R"(},
      "lights": [{"type": "environment", "color": [0.3, 0.35, 0.45]},
                 {"type": "sphere", "center": [2, 3, 1], "radius": 0.6, "intensity": 6}],
      "objects": [{"name": "ball", "mesh": "procedural:icosphere:3"},
                  {"name": "ground", "mesh": "procedural:plane:1x1",
                   "transform": {"scale": 8, "translate": [0, -1, 0]}}]})";
}

double mse(const std::vector<float> &a, const std::vector<float> &b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += double(a[i] - b[i]) * (a[i] - b[i]);
    return s / double(a.size());
}

TEST(DenoiseCli, TheExrKeepsTheNoisyBeautyAndAddsACleanerDenoisedLayer) {
    TempDir tmp;
    const std::string noisy =
        tmp.write("noisy.json", lit_scene(8, R"(, "cryptomatte": true)"));
    const std::string dn =
        tmp.write("dn.json", lit_scene(8, R"(, "cryptomatte": true, "denoise": true)"));
    const std::string ref = tmp.write("ref.json", lit_scene(1024));
    std::string out, err;
    ASSERT_EQ(run_pelage("render " + noisy + " -q -o " + tmp.file("noisy.exr")), 0);
    ASSERT_EQ(run_pelage("render " + dn + " -o " + tmp.file("dn.exr") + " --preview " +
                             tmp.file("dn.png") + " --stats-json " + tmp.file("s.json"),
                         &out, &err),
              0)
        << err;
    ASSERT_EQ(run_pelage("render " + ref + " -q -o " + tmp.file("ref.exr")), 0);
    const Exr a = read_exr(tmp.file("noisy.exr")), d = read_exr(tmp.file("dn.exr")),
              r = read_exr(tmp.file("ref.exr"));
    ASSERT_EQ(d.width, 64);
    // Every layer of the plain render is in the denoised one with the same values
    // (the beauty stays noisy, Cryptomatte is never denoised), plus denoised.R/G/B.
    for (const std::string &name : a.names) {
        const std::vector<float> x = a.channel(name), y = d.channel(name);
        ASSERT_EQ(x.size(), y.size()) << name;
        for (size_t i = 0; i < x.size(); ++i)
            ASSERT_TRUE(x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i])))
                << name << " pixel " << i;
    }
    EXPECT_EQ(d.names.size(), a.names.size() + 3);
    double noisy_mse = 0, denoised_mse = 0;
    for (const char *c : {"R", "G", "B"}) {
        const std::vector<float> den = d.channel(std::string("denoised.") + c);
        ASSERT_EQ(den.size(), size_t(64 * 48)) << c;
        for (float v : den) ASSERT_TRUE(std::isfinite(v));
        noisy_mse += mse(a.channel(c), r.channel(c));
        denoised_mse += mse(den, r.channel(c));
    }
    EXPECT_LT(denoised_mse * 3, noisy_mse)
        << "noisy MSE " << noisy_mse << ", denoised " << denoised_mse;

    // The preview shows the denoised image: its neighbouring pixels differ less than
    // those of the noisy render's preview.
    ASSERT_EQ(run_pelage("render " + noisy + " -q -o " + tmp.file("n2.exr") +
                         " --preview " + tmp.file("noisy.png")),
              0);
    auto roughness = [](const std::vector<unsigned char> &px) {
        double s = 0;
        for (size_t i = 3; i < px.size(); ++i) s += std::abs(int(px[i]) - int(px[i - 3]));
        return s;
    };
    const auto pd = read_png(tmp.file("dn.png")), pn = read_png(tmp.file("noisy.png"));
    ASSERT_EQ(pd.size(), pn.size());
    EXPECT_LT(roughness(pd), 0.8 * roughness(pn));

    const nlohmann::json stats = nlohmann::json::parse(slurp(tmp.file("s.json")));
    EXPECT_GT(stats.at("denoise_seconds").get<double>(), 0.0);
    EXPECT_NE(out.find(", denoise "), std::string::npos) << "the summary line: " << out;
}

TEST(DenoiseCli, TheSameBytesAtAnyThreadCount) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", lit_scene(4, R"(, "denoise": true)"));
    ASSERT_EQ(run_pelage("render " + scene + " -q --threads 1 -o " + tmp.file("1.exr")),
              0);
    ASSERT_EQ(run_pelage("render " + scene + " -q --threads 2 -o " + tmp.file("2.exr")),
              0);
    const std::string a = slurp(tmp.file("1.exr")), b = slurp(tmp.file("2.exr"));
    ASSERT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == b);
}

TEST(DenoiseCli, OneSamplePerPixelIsKeptNoisyWithAWarning) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", lit_scene(1));
    std::string out, err;
    ASSERT_EQ(
        run_pelage("render " + scene + " --denoise -o " + tmp.file("o.exr"), &out, &err),
        0)
        << err;
    EXPECT_NE(err.find("2 samples per pixel"), std::string::npos) << err;
    const Exr e = read_exr(tmp.file("o.exr"));
    for (const char *c : {"R", "G", "B"}) {
        const std::vector<float> n = e.channel(c),
                                 d = e.channel(std::string("denoised.") + c);
        ASSERT_EQ(n.size(), d.size());
        for (size_t i = 0; i < n.size(); ++i) EXPECT_NEAR(d[i], n[i], 1e-3f * (1 + n[i]));
    }
}

TEST(DenoiseCli, LookWritesTheDenoiseIntoItsScene) {
    TempDir tmp;
    std::string out, err;
    ASSERT_EQ(
        run_pelage("look procedural:icosphere:3 --preset " + two_type_preset(tmp, 200) +
                       " --res 48x32 --spp 4 --denoise -q -o " + tmp.file("l.exr"),
                   &out, &err),
        0)
        << err;
    const nlohmann::json scene = nlohmann::json::parse(slurp(tmp.file("l.json")));
    EXPECT_TRUE(scene.at("film").at("denoise").get<bool>());
    const Exr e = read_exr(tmp.file("l.exr"));
    EXPECT_FALSE(e.channel("denoised.G").empty());
}

}  // namespace
}  // namespace pelage::test
