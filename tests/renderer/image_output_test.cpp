// EXR layers, channel names and metadata survive a round trip through OpenImageIO; the
// PNG preview goes through OpenColorIO.
#include "renderer/image_output.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "renderer/color_management.h"
#include "renderer/film.h"
#include "sim/input_error.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using namespace pelage::renderer;

TEST(ImageOutput, ExrRoundTripKeepsLayersChannelNamesAndMetadata) {
    TempDir tmp;
    const int W = 5, H = 3, nc = Film::num_channels;
    std::vector<float> px(size_t(W) * H * nc);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 97) * 0.25f;
    const auto names = Film::channel_names({"cell_id", "cell_type"});
    ImageMetadata meta{"/scenes/x.json", "pelage test", 64, 12345678901ull, 1.5, false};
    const std::string path = tmp.file("out.exr");
    write_exr(path, W, H, px, names, true, meta);

    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec &spec = in->spec();
    EXPECT_EQ(spec.width, W);
    EXPECT_EQ(spec.height, H);
    ASSERT_EQ(spec.nchannels, nc);
    // OpenEXR sorts channels by name on disk; compare as sets, then read by name.
    std::vector<std::string> got(spec.channelnames.begin(), spec.channelnames.end());
    std::vector<std::string> want = names;
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
    for (const char *n :
         {"R", "G", "B", "A", "albedo.R", "N.X", "depth.Z", "id.object", "id.primitive",
          "shader.cell_id", "shader.cell_type", "shader.2"})
        EXPECT_NE(std::find(got.begin(), got.end(), n), got.end()) << n;
    EXPECT_EQ(spec.get_int_attribute("pelage:spp"), 64);
    EXPECT_EQ(spec.get_string_attribute("pelage:seed"), "12345678901");
    EXPECT_EQ(spec.get_string_attribute("pelage:scene"), "/scenes/x.json");
    EXPECT_EQ(spec.get_string_attribute("Software"), "pelage test");
    EXPECT_FLOAT_EQ(spec.get_float_attribute("pelage:render_seconds"), 1.5f);
    // Ids are float (exact), colours half.
    std::vector<float> back(px.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, back.data()));
    for (int c = 0; c < nc; ++c) {
        const std::string &n = spec.channelnames[c];
        const int src = int(std::find(names.begin(), names.end(), n) - names.begin());
        const OIIO::TypeDesc fmt =
            spec.channelformats.empty() ? spec.format : spec.channelformats[c];
        const bool exact = n.rfind("id.", 0) == 0 || n.rfind("depth.", 0) == 0 ||
                           n.rfind("shader.", 0) == 0;
        EXPECT_EQ(fmt, exact ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF) << n;
        for (int i = 0; i < W * H; ++i)
            EXPECT_FLOAT_EQ(back[size_t(i) * nc + c], px[size_t(i) * nc + src])
                << n;  // values are exact in half
    }
    // Nothing but the final file is left in the folder (atomic write).
    size_t files = 0;
    for (const auto &e : std::filesystem::directory_iterator(tmp.path())) {
        (void)e;
        ++files;
    }
    EXPECT_EQ(files, 1u);
}

TEST(ColorManagement, LinearMidGreyMapsToSrgbCode118ThroughTheStandardView) {
    TempDir tmp;
    unsetenv("OCIO");
    const DisplayTransform display("Standard", "sRGB");
    const int W = 4, H = 2;
    std::vector<float> px(size_t(W) * H * 4, 0.18f);
    const std::string path = tmp.file("grey.png");
    write_preview(path, W, H, px, 4, display);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    std::vector<unsigned char> b(size_t(W) * H * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, b.data()));
    // sRGB OETF: 1.055 · 0.18^(1/2.4) − 0.055 = 0.4614 → 0.4614 · 255 = 117.7 → 118.
    for (unsigned char v : b) EXPECT_EQ(int(v), 118);
}

TEST(ColorManagement, FilmicViewIsMonotonicAndRollsOffHighlights) {
    const DisplayTransform filmic("Filmic", "sRGB");
    float rgb[] = {0.01f, 0.01f, 0.01f, 0.18f, 0.18f, 0.18f,
                   1.0f,  1.0f,  1.0f,  16.0f, 16.0f, 16.0f};
    filmic.apply_rgb(rgb, 4);
    EXPECT_LT(rgb[0], rgb[3]);
    EXPECT_LT(rgb[3], rgb[6]);
    EXPECT_LT(rgb[6], rgb[9]);
    EXPECT_GT(rgb[3], 0.3f);  // mid grey stays mid
    EXPECT_LT(rgb[3], 0.6f);
    EXPECT_LE(rgb[9], 1.0f);  // 16× mid-grey-ish is not clipped flat below 1
}

TEST(ColorManagement, UnknownViewIsAnInputErrorNamingTheField) {
    try {
        DisplayTransform d("Filmmic", "sRGB");
        FAIL() << "no error";
    } catch (const InputError &e) {
        EXPECT_EQ(e.field(), "film.view");
        EXPECT_NE(std::string(e.what()).find("Filmmic"), std::string::npos);
    }
}

TEST(ColorManagement, OcioEnvironmentVariableSelectsTheConfig) {
    TempDir tmp;
    const std::string cfg = tmp.write("raw.ocio", R"(ocio_profile_version: 2
roles:
  default: lin
  scene_linear: lin
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  Only:
    - !<View> {name: Passthrough, colorspace: lin}
colorspaces:
  - !<ColorSpace>
    name: lin
)");
    setenv("OCIO", cfg.c_str(), 1);
    const DisplayTransform d("", "");
    unsetenv("OCIO");
    EXPECT_EQ(d.config_path(), cfg);
    EXPECT_EQ(d.display(), "Only");
    EXPECT_EQ(d.view(), "Passthrough");
    float rgb[3] = {0.18f, 0.5f, 2.0f};
    d.apply_rgb(rgb, 1);
    EXPECT_FLOAT_EQ(rgb[0], 0.18f);
    EXPECT_FLOAT_EQ(rgb[2], 2.0f);
}

}  // namespace
}  // namespace pelage::test
