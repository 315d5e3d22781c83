// The texture plugin through the plugin ABI: 8-bit sRGB images decode to the analytic
// sRGB curve (IEC 61966-2-1), float EXRs read as they are, a `colorspace` parameter
// overrides the file's, wrap modes behave as named, and UDIM tiles are chosen by the UV's
// integer parts with v running up within each tile.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "renderer/plugins/plugin_loader.h"
#include "tests/shader/plugin_mesh_view.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

std::string plugin_file() {
    return (std::filesystem::path(PELAGE_BINARY).parent_path().parent_path() /
            "lib/pelage/shaders/texture.so")
        .string();
}

// A one-triangle mesh with UVs: the plugin only needs their presence.
struct Instance {
    renderer::LoadedPlugin plugin;
    renderer::PluginParams params;
    PluginMeshView view{PluginMeshView::unit_triangle(), "test", nullptr};
    void *self = nullptr;
    std::string error;

    explicit Instance(const nlohmann::json &p)
        : plugin(renderer::open_plugin(plugin_file())),
          params(
              renderer::validate_plugin_params(*plugin.desc, p, "test.json", "params")) {
        PelageParamSet ps{};
        ps.count = uint32_t(params.values.size());
        ps.values = params.values.data();
        ps.mesh = view.view;
        ps.warn = PluginMeshView::warn;
        ps.scene_dir = "";
        ps.object_name = "test";
        PelageError err{};
        self = plugin.desc->create(&ps, &err);
        error = err.message;
    }
    ~Instance() {
        if (self) plugin.desc->destroy(self);
    }
    std::array<float, 3> at(float u, float v) const {
        PelageHit hit{};
        hit.uv[0] = u;
        hit.uv[1] = v;
        hit.has_uv = 1;
        PelageShade out{};
        plugin.desc->shade(self, &hit, &out);
        return {out.albedo[0], out.albedo[1], out.albedo[2]};
    }
};

// Writes a w x h image whose pixel (x, y) is colour(x, y) (RGB), as `format`.
template <typename F>
void write_image(const std::string &path, int w, int h, OIIO::TypeDesc format, F colour) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::array<float, 3> c = colour(x, y);
            buf.setpixel(x, y, c.data());
        }
    buf.set_write_format(format);
    ASSERT_TRUE(buf.write(path)) << buf.geterror();
}

double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(TexturePlugin, SrgbPngDecodesToTheAnalyticCurve) {
    TempDir tmp;
    const std::string png = tmp.file("ramp.png");
    write_image(png, 256, 1, OIIO::TypeDesc::UINT8, [](int x, int) {
        const float c = float(x) / 255;
        return std::array<float, 3>{c, c, c};
    });
    const Instance tex(nlohmann::json{{"file", png}});
    ASSERT_TRUE(tex.self) << tex.error;
    const Instance raw(nlohmann::json{{"file", png}, {"colorspace", "linear"}});
    ASSERT_TRUE(raw.self) << raw.error;
    for (int x = 0; x < 256; ++x) {
        // Texel centres: the bilinear lookup returns the texel itself.
        const float u = (x + 0.5f) / 256;
        EXPECT_NEAR(tex.at(u, 0.5f)[0], srgb_to_linear(x / 255.0), 2e-4) << x;
        EXPECT_NEAR(raw.at(u, 0.5f)[1], x / 255.0, 2e-4) << x;
    }
}

TEST(TexturePlugin, FloatExrIsLinearAndAColourSpaceConvertsIt) {
    TempDir tmp;
    const std::string exr = tmp.file("grey.exr");
    write_image(exr, 4, 4, OIIO::TypeDesc::FLOAT, [](int, int) {
        return std::array<float, 3>{0.5f, 0.25f, 0.75f};
    });
    const Instance tex(nlohmann::json{{"file", exr}});
    ASSERT_TRUE(tex.self) << tex.error;
    EXPECT_NEAR(tex.at(0.4f, 0.6f)[0], 0.5f, 1e-6);
    EXPECT_NEAR(tex.at(0.4f, 0.6f)[2], 0.75f, 1e-6);
    const Instance as_srgb(nlohmann::json{{"file", exr}, {"colorspace", "sRGB"}});
    ASSERT_TRUE(as_srgb.self) << as_srgb.error;
    EXPECT_NEAR(as_srgb.at(0.4f, 0.6f)[1], srgb_to_linear(0.25), 2e-4);
    const Instance bad(nlohmann::json{{"file", exr}, {"colorspace", "no such space"}});
    EXPECT_FALSE(bad.self);
    EXPECT_NE(bad.error.find("colorspace"), std::string::npos) << bad.error;
}

TEST(TexturePlugin, PeriodicWrapTilesAndClampHoldsTheEdge) {
    TempDir tmp;
    const std::string exr = tmp.file("row.exr");
    const float value[4] = {0.1f, 0.3f, 0.6f, 0.9f};
    write_image(exr, 4, 1, OIIO::TypeDesc::FLOAT, [&](int x, int) {
        return std::array<float, 3>{value[x], value[x], value[x]};
    });
    const Instance clamp(nlohmann::json{{"file", exr}});
    const Instance periodic(nlohmann::json{{"file", exr}, {"wrap", "periodic"}});
    const Instance black(nlohmann::json{{"file", exr}, {"wrap", "black"}});
    ASSERT_TRUE(clamp.self && periodic.self && black.self);
    // Texel centres one period to the right and to the left.
    EXPECT_NEAR(periodic.at(1.125f, 0.5f)[0], 0.1f, 1e-5);
    EXPECT_NEAR(periodic.at(-0.375f, 0.5f)[0], 0.6f, 1e-5);
    EXPECT_NEAR(clamp.at(1.125f, 0.5f)[0], 0.9f, 1e-5);
    EXPECT_NEAR(clamp.at(-0.375f, 0.5f)[0], 0.1f, 1e-5);
    EXPECT_NEAR(black.at(1.625f, 0.5f)[0], 0.0f, 1e-5);
    // Inside [0, 1] the modes agree.
    EXPECT_NEAR(periodic.at(0.625f, 0.5f)[0], clamp.at(0.625f, 0.5f)[0], 1e-6);
    const Instance bad(nlohmann::json{{"file", exr}, {"wrap", "repeat"}});
    EXPECT_FALSE(bad.self);
    EXPECT_NE(bad.error.find("wrap"), std::string::npos) << bad.error;
}

TEST(TexturePlugin, UdimLookupPicksTheTileOfTheUv) {
    TempDir tmp;
    // 1001 red, 1002 green; 1011 blue in its bottom half (v < 0.5 within the tile), white
    // in its top half; no 1012.
    write_image(tmp.file("t.1001.exr"), 8, 8, OIIO::TypeDesc::FLOAT, [](int, int) {
        return std::array<float, 3>{1, 0, 0};
    });
    write_image(tmp.file("t.1002.exr"), 8, 8, OIIO::TypeDesc::FLOAT, [](int, int) {
        return std::array<float, 3>{0, 1, 0};
    });
    write_image(tmp.file("t.1011.exr"), 8, 8, OIIO::TypeDesc::FLOAT, [](int, int y) {
        return y >= 4 ? std::array<float, 3>{0, 0, 1} : std::array<float, 3>{1, 1, 1};
    });
    const Instance tex(nlohmann::json{{"file", tmp.file("t.<UDIM>.exr")}});
    ASSERT_TRUE(tex.self) << tex.error;
    const auto red = tex.at(0.5f, 0.5f), green = tex.at(1.5f, 0.3f),
               blue = tex.at(0.5f, 1.2f), white = tex.at(0.5f, 1.8f),
               missing = tex.at(1.5f, 1.5f);
    EXPECT_NEAR(red[0], 1, 1e-5);
    EXPECT_NEAR(red[1], 0, 1e-5);
    EXPECT_NEAR(green[1], 1, 1e-5);
    EXPECT_NEAR(green[0], 0, 1e-5);
    EXPECT_NEAR(blue[2], 1, 1e-5);
    EXPECT_NEAR(blue[0], 0, 1e-5);
    EXPECT_NEAR(white[0], 1, 1e-5);
    EXPECT_NEAR(missing[0] + missing[1] + missing[2], 0, 1e-5);

    const Instance none(nlohmann::json{{"file", tmp.file("u.<UDIM>.exr")}});
    EXPECT_FALSE(none.self);
    EXPECT_NE(none.error.find("UDIM"), std::string::npos) << none.error;
}

}  // namespace
}  // namespace pelage::test
