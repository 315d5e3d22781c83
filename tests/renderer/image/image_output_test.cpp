// EXR layers, channel names and metadata survive a round trip through OpenImageIO; the
// PNG preview goes through OpenColorIO.
#include "renderer/image/image_output.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "renderer/image/color_management.h"
#include "renderer/image/film.h"
#include "sim/core/input_error.h"
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
    ImageMetadata meta;
    meta.scene = "/scenes/x.json";
    meta.software = "pelage test";
    meta.spp = 64;
    meta.seed = 12345678901ull;
    meta.render_seconds = 1.5;
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
    EXPECT_EQ(spec.find_attribute("pelage:view"), nullptr);  // none given, none written
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

    // The view the render is meant for, for `pelage movie`.
    meta.view = "Filmic";
    write_exr(path, W, H, px, names, true, meta);
    auto with_view = OIIO::ImageInput::open(path);
    ASSERT_TRUE(with_view);
    EXPECT_EQ(with_view->spec().get_string_attribute("pelage:view"), "Filmic");
}

// The stored bytes of an EXR, channel formats as written, and its spec.
std::vector<unsigned char> native_pixels(const std::string &path, OIIO::ImageSpec &spec) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << OIIO::geterror();
    spec = in->spec();
    std::vector<unsigned char> native(spec.image_bytes(true));
    EXPECT_TRUE(
        in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UNKNOWN, native.data()));
    return native;
}

void rewrite(const std::string &path, const OIIO::ImageSpec &spec,
             const std::vector<unsigned char> &native) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) &&
                out->write_image(OIIO::TypeDesc::UNKNOWN, native.data()) && out->close());
}

// --resume trusts a frame only when its pixels hash to the header's checksum, whatever
// order OpenEXR gives the channels back in; older files carry an FNV-1a
// pelage:pixel_hash instead of the XXH3 one, which must still verify.
TEST(ImageOutput, PixelChecksumMarksCompleteFramesAndLegacyFnvStillVerifies) {
    TempDir tmp;
    const int W = 7, H = 5, nc = Film::num_channels;
    std::vector<float> px(size_t(W) * H * nc);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 89) * 0.125f;
    const auto names = Film::channel_names({"cell_id"});
    ImageMetadata meta;
    meta.scene = "/scenes/x.json";
    meta.software = "pelage test";
    meta.spp = 4;
    meta.seed = 7;
    meta.render_seconds = 0.5;
    const std::string path = tmp.file("frame.exr");
    write_exr(path, W, H, px, names, true, meta);
    std::string why;
    EXPECT_TRUE(exr_is_complete(path, &why)) << why;

    OIIO::ImageSpec spec;
    std::vector<unsigned char> native = native_pixels(path, spec);
    std::vector<int> sizes(spec.nchannels);
    for (int c = 0; c < spec.nchannels; ++c) sizes[c] = int(spec.channelformat(c).size());
    const uint64_t h = pixel_hash(native.data(), size_t(W) * H, spec.channelnames, sizes);
    // Channel order does not matter: the same pixels with channels 0 and 1 swapped.
    {
        std::vector<std::string> swapped_names = spec.channelnames;
        std::swap(swapped_names[0], swapped_names[1]);
        std::vector<int> swapped_sizes = sizes;
        std::swap(swapped_sizes[0], swapped_sizes[1]);
        const size_t stride = spec.pixel_bytes(true);
        std::vector<unsigned char> swapped(native.size());
        for (size_t i = 0; i < size_t(W) * H; ++i) {
            const unsigned char *p = &native[i * stride];
            unsigned char *q = &swapped[i * stride];
            std::memcpy(q, p + sizes[0], size_t(sizes[1]));
            std::memcpy(q + sizes[1], p, size_t(sizes[0]));
            std::memcpy(q + sizes[0] + sizes[1], p + sizes[0] + sizes[1],
                        stride - size_t(sizes[0] + sizes[1]));
        }
        EXPECT_EQ(pixel_hash(swapped.data(), size_t(W) * H, swapped_names, swapped_sizes),
                  h);
    }
    // One changed byte: another checksum, and the file is no longer complete.
    native[native.size() / 2] ^= 0x40;
    EXPECT_NE(pixel_hash(native.data(), size_t(W) * H, spec.channelnames, sizes), h);
    rewrite(path, spec, native);
    EXPECT_FALSE(exr_is_complete(path, &why));
    EXPECT_EQ(why, "pixel checksum mismatch");

    // A legacy file: FNV-1a 64 over each channel's name and bytes, in name order.
    std::vector<size_t> order(spec.nchannels), offset(spec.nchannels);
    size_t stride = 0;
    for (int c = 0; c < spec.nchannels; ++c) {
        order[c] = size_t(c);
        offset[c] = stride;
        stride += size_t(sizes[c]);
    }
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return spec.channelnames[a] < spec.channelnames[b];
    });
    uint64_t fnv = 0xcbf29ce484222325ull;
    for (const size_t c : order) {
        for (const char ch : spec.channelnames[c])
            fnv = (fnv ^ static_cast<unsigned char>(ch)) * 0x100000001b3ull;
        for (size_t i = 0; i < size_t(W) * H; ++i)
            for (int k = 0; k < sizes[c]; ++k)
                fnv =
                    (fnv ^ native[i * stride + offset[c] + size_t(k)]) * 0x100000001b3ull;
    }
    OIIO::ImageSpec legacy = spec;
    legacy.erase_attribute("pelage:pixel_xxh3");
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv));
    legacy.attribute("pelage:pixel_hash", hex);
    rewrite(path, legacy, native);
    EXPECT_TRUE(exr_is_complete(path, &why)) << why;
    legacy.attribute("pelage:pixel_hash", "0123456789abcdef");
    rewrite(path, legacy, native);
    EXPECT_FALSE(exr_is_complete(path, &why));
    // Neither checksum: not a pelage frame.
    legacy.erase_attribute("pelage:pixel_hash");
    rewrite(path, legacy, native);
    EXPECT_FALSE(exr_is_complete(path, &why));
    EXPECT_EQ(why, "no pelage:pixel_xxh3 in the header");
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
