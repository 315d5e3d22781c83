// Fur in the renderer: strands take the skin plugin's pigment at their roots, a furry
// render is finite, differs from the bare skin and is the same at 1 and 2 threads, and
// a non-absorbing coat in a white furnace returns the environment's radiance.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "renderer/bsdf/hair_pigments.h"
#include "renderer/geometry/embree_ray.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/renderer/render_helpers.h"

namespace pelage::test {
namespace {

// A unit sphere with `skin` material JSON and `fur` (JSON or "" for none), seen from the
// front under `lights`.
std::string fur_scene(const std::string &skin, const std::string &fur, int size, int spp,
                      const std::string &lights, int max_depth = 6) {
    return R"({"camera": {"position": [0, 0, 3.2], "look_at": [0, 0, 0], "fov": 42},
      "film": {"width": )" +
           std::to_string(size) + R"(, "height": )" + std::to_string(size) +
           R"(, "spp": )" + std::to_string(spp) + R"(, "filter": {"type": "box"}},
      "lights": )" +
           lights + R"(,
      "objects": [{"mesh": "procedural:sphere:16x16", "normals": "smooth", "material": )" +
           skin + (fur.empty() ? "" : R"(, "fur": )" + fur) + R"(}],
      "integrator": {"max_depth": )" +
           std::to_string(max_depth) + R"(, "rr_depth": 4}})";
}

const std::string sun_and_sky =
    R"([{"type": "environment", "color": [0.5, 0.6, 0.8]},
        {"type": "distant", "direction": [-0.5, -0.7, -0.5], "intensity": 3}])";
const std::string grey_skin = R"({"shader": "diffuse", "params": {"albedo": 0.5}})";
const std::string coat =
    R"({"density": 3000, "length": 0.15, "root_radius": 0.004, "tip_radius": 0.001,
        "gravity": 0.3, "clump": 0.3, "clump_radius": 0.05, "seed": 3})";

double mean_channel(const RenderedImage &im, int c) {
    double s = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) s += im.at(x, y, c);
    return s / (double(im.width) * im.height);
}

TEST(FurRender, FiniteDiffersFromBareSkinAndSameAtOneAndTwoThreads) {
    TempDir tmp;
    const RenderedImage bare =
        render_json(fur_scene(grey_skin, "", 40, 4, sun_and_sky), tmp);
    const RenderedImage furry =
        render_json(fur_scene(grey_skin, coat, 40, 4, sun_and_sky), tmp, 1);
    const RenderedImage furry2 =
        render_json(fur_scene(grey_skin, coat, 40, 4, sun_and_sky), tmp, 2);
    EXPECT_EQ(furry.stats.nonfinite_samples, 0u);
    double diff = 0;
    for (size_t i = 0; i < furry.pixels.size(); ++i) {
        // Depth (channel 10) is +inf where nothing was hit, in both images.
        if (i % renderer::Film::num_channels == 10 && std::isinf(furry.pixels[i])) {
            ASSERT_GT(furry.pixels[i], 0) << i;
            continue;
        }
        ASSERT_TRUE(std::isfinite(furry.pixels[i])) << i;
        diff += std::abs(furry.pixels[i] - bare.pixels[i]);
    }
    EXPECT_GT(diff / double(furry.pixels.size()), 0.01);
    EXPECT_EQ(furry.pixels, furry2.pixels);
}

// An independent reference for a fibre's shading as rendered (geometry, the offset h
// across the tube, the BSDF and the sky's sampling together): under a uniform sky of
// radiance 1, an isolated fibre seen across its axis shows Σ_p A_p(h), since M_p and
// N_p integrate to one over the sphere (Chiang et al. 2016, §3; pbrt-v4's white
// furnace test), A_p the attenuations of the Fresnel factor f and the transmittance T at
// h (Chiang et al. 2016, Eq. 3-4). Written here from the paper, not from renderer/bsdf.
// One thick fibre stands on a plane too small to see or to shadow it.
double fresnel_reference(double cos_i, double eta) {
    const double sin_t2 = (1 - cos_i * cos_i) / (eta * eta);
    const double cos_t = std::sqrt(std::max(0.0, 1 - sin_t2));
    const double r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (r_par * r_par + r_perp * r_perp) / 2;
}

// Σ_p A_p at offset h for a ray perpendicular to the fibre (θ_o = 0).
double attenuation_sum(double h, double sigma_a, double eta) {
    const double f = fresnel_reference(std::sqrt(1 - h * h), eta);
    const double sin_gt = h / eta;
    const double T = std::exp(-sigma_a * 2 * std::sqrt(1 - sin_gt * sin_gt));
    const double a1 = (1 - f) * (1 - f) * T, a2 = a1 * T * f;
    return f + a1 + a2 + a2 * T * f / (1 - T * f);
}

TEST(FurRender, AnIsolatedFibreUnderAUniformSkyShowsItsAttenuationsSum) {
    TempDir tmp;
    // The root lies anywhere on the speck: 1e-4 across keeps the axis within 0.1 % of the
    // radius of x = 0.
    sim::write_obj(tmp.file("speck.obj"), sim::make_plane(1, 1, 1e-4, 1e-4), {});
    const double sigma[3] = {0.3, 1.2, 3.1}, eta = 1.55, radius = 0.05, dist = 3;
    const int W = 64, H = 48;
    const double fov = 10;
    const std::string scene =
        R"({"camera": {"position": [0, 0.5, 3], "look_at": [0, 0.5, 0], "fov": 10},
      "film": {"width": 64, "height": 48, "spp": 512, "filter": {"type": "box"}},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"mesh": ")" +
        tmp.file("speck.obj") +
        R"(", "material": {"shader": "diffuse", "params": {"albedo": 0}},
        "fur": {"density": 1e8, "length": 1, "length_variation": 0,
                "root_radius": 0.05, "tip_radius": 0.05, "comb": "normal",
                "comb_jitter": 0, "sigma_a": [0.3, 1.2, 3.1], "melanin_jitter": 0,
                "seed": 1}}],
      "integrator": {"max_depth": 4, "rr_depth": 4}})";
    const RenderedImage im = render_json(scene, tmp);
    // Columns the fibre covers fully; the five rows about the axis's middle (θ_o within
    // 0.6° of 0). Each column's expected value averages Σ A_p over the offsets its box
    // filter's samples cross.
    const double pix = 2 * std::tan(fov / 2 * 3.14159265358979 / 180) / H;
    int columns = 0;
    for (int x = 0; x < W; ++x) {
        auto h_at = [&](double sx) {
            const double u = (sx - W / 2.0) * pix;
            return dist * u / std::sqrt(1 + u * u) / radius;
        };
        if (std::abs(h_at(x)) >= 1 || std::abs(h_at(x + 1)) >= 1) continue;
        ++columns;
        for (int c = 0; c < 3; ++c) {
            double want = 0;
            const int n = 2000;
            for (int k = 0; k < n; ++k)
                want += attenuation_sum(h_at(x + (k + 0.5) / n), sigma[c], eta) / n;
            double got = 0;
            for (int y = H / 2 - 2; y <= H / 2 + 2; ++y) got += im.at(x, y, c) / 5;
            EXPECT_NEAR(got, want, 0.03 * want) << "column " << x << ", channel " << c;
        }
    }
    EXPECT_GE(columns, 6);
    EXPECT_EQ(im.stats.nonfinite_samples, 0u);
}

// Flat ribbons (the distance option) shade through the same hair path: finite, and
// close to the round tubes' brightness (same strands, same BSDF; the ribbon's h is
// rebuilt from the hit's offset, so only the silhouettes differ).
TEST(FurRender, FlatRibbonsLookLikeRoundTubes) {
    TempDir tmp;
    std::string flat = coat;
    flat.insert(flat.find('}'), R"(, "curve": "flat")");
    // Converged, the ribbons are 12 % brighter here; 64 spp keeps the noise of the
    // means under 1 %.
    const RenderedImage round =
        render_json(fur_scene(grey_skin, coat, 32, 64, sun_and_sky), tmp);
    const RenderedImage ribbons =
        render_json(fur_scene(grey_skin, flat, 32, 64, sun_and_sky), tmp);
    EXPECT_EQ(ribbons.stats.nonfinite_samples, 0u);
    EXPECT_NE(ribbons.pixels, round.pixels);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(mean_channel(ribbons, c), mean_channel(round, c),
                    0.15 * mean_channel(round, c))
            << c;
}

// min_pixel_width widens exactly the control points whose radius is under half that
// many pixels at their distance from the camera (pixel angle 2 tan(fov/2) / height), to
// that radius, keeps their own radii, and their opacity is own / widened radius.
TEST(FurRender, MinPixelWidthWidensSubPixelStrandsToIt) {
    const std::string thin =
        R"({"density": 3000, "length": 0.15, "root_radius": 0.003, "tip_radius": 0.001,
            "seed": 3, "min_pixel_width": )";
    const renderer::PluginRegistry plugins;
    auto build = [&](const char *width) {
        return renderer::Scene(
            renderer::parse_scene(fur_scene(grey_skin, thin + width + "}", 32, 1, "[]"),
                                  "fur.json"),
            plugins);
    };
    const renderer::Scene off = build("0"), wide = build("2");
    EXPECT_FALSE(off.fur()->widened());
    ASSERT_TRUE(wide.fur()->widened());
    const renderer::FurLayer &a = off.fur()->layers().at(0),
                             &b = wide.fur()->layers().at(0);
    ASSERT_EQ(a.strands.points, b.strands.points);  // the fibres stay as they grew
    ASSERT_EQ(b.wide_points.size(), b.strands.points.size());
    EXPECT_TRUE(a.wide_points.empty());
    EXPECT_EQ(off.fur()->camera_scene(), nullptr);
    EXPECT_NE(wide.fur()->camera_scene(), nullptr);
    // Camera at (0, 0, 3.2), fov 42°, 32 rows: a two-pixel-wide strand's radius per
    // unit of distance.
    const float k = 2 * std::tan(21 * 3.14159265f / 180) / 32;
    size_t widened = 0;
    for (size_t j = 0; j < b.wide_points.size() / 4; ++j) {
        const float *P = &b.wide_points[4 * j];
        const Vec3f e = Vec3f{P[0], P[1], P[2]} - Vec3f{0, 0, 3.2f};
        const float own = b.strands.points[4 * j + 3];
        ASSERT_EQ(P[0], b.strands.points[4 * j]);
        ASSERT_NEAR(P[3], std::max(own, k * length(e)), 1e-6f * length(e));
        widened += P[3] > own;
    }
    EXPECT_GT(widened, b.wide_points.size() / 8);
    const int S = b.strands.segments;
    for (unsigned prim = 0; prim < 50; ++prim) {
        const size_t first =
            size_t(prim / unsigned(S)) * b.strands.points_per_strand + prim % unsigned(S);
        // u = 0 on a uniform B-spline: (P0 + 4 P1 + P2) / 6 of either radius.
        auto blend = [&](auto r) {
            return (r(first) + 4 * r(first + 1) + r(first + 2)) / 6;
        };
        const float own = blend([&](size_t j) { return b.strands.points[4 * j + 3]; });
        const float w = blend([&](size_t j) { return b.wide_points[4 * j + 3]; });
        EXPECT_NEAR(b.opacity(prim, 0), own / w, 1e-5f);
        EXPECT_EQ(a.opacity(prim, 0), 1.0f);
    }
}

// σ_a = 0 fibres (the diffuse skin has no melanin) on a white Lambertian skin, inside a
// uniform environment of radiance 1: nothing absorbs, so every pixel converges to 1
// (the hair BSDF conserves energy to ~1 %, renderer/bsdf/hair_bsdf_test.cpp). The same
// coat on a grey skin must lose energy: the test can fail.
TEST(FurRender, WhiteFurnaceReturnsTheEnvironment) {
    TempDir tmp;
    const std::string white_env = R"([{"type": "environment", "color": [1, 1, 1]}])";
    const std::string white_skin = R"({"shader": "diffuse", "params": {"albedo": 1}})";
    const RenderedImage white =
        render_json(fur_scene(white_skin, coat, 24, 32, white_env, 200), tmp);
    EXPECT_EQ(white.stats.nonfinite_samples, 0u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_channel(white, c), 1.0, 0.03) << c;
    const RenderedImage grey =
        render_json(fur_scene(grey_skin, coat, 24, 32, white_env, 200), tmp);
    EXPECT_LT(mean_channel(grey, 1), 0.95);
}

std::string with_bounce_roughness(std::string scene, float roughness) {
    const std::string key = R"("rr_depth": 4)";
    return scene.replace(
        scene.find(key), key.size(),
        key + R"(, "fur_bounce_roughness": )" + std::to_string(roughness));
}

// Path regularisation (integrator.fur_bounce_roughness) widens lobes that stay
// normalised: the white furnace still returns the environment at its widest.
TEST(FurRender, ARegularisedWhiteFurnaceReturnsTheEnvironment) {
    TempDir tmp;
    const std::string white_env = R"([{"type": "environment", "color": [1, 1, 1]}])";
    const std::string white_skin = R"({"shader": "diffuse", "params": {"albedo": 1}})";
    const RenderedImage white = render_json(
        with_bounce_roughness(fur_scene(white_skin, coat, 24, 32, white_env, 200), 1),
        tmp);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_channel(white, c), 1.0, 0.03) << c;
}

// ... and only where a bounce reaches a strand: with direct light alone (max_depth 1)
// the image is the same at any value, bit for bit; with bounces it changes.
TEST(FurRender, BounceRoughnessLeavesTheCameraHitsAlone) {
    TempDir tmp;
    auto render = [&](int max_depth, float roughness) {
        return render_json(
            with_bounce_roughness(
                fur_scene(grey_skin, coat, 24, 16, sun_and_sky, max_depth), roughness),
            tmp);
    };
    const RenderedImage direct0 = render(1, 0), direct1 = render(1, 1);
    const RenderedImage bounced0 = render(4, 0), bounced1 = render(4, 1);
    double direct_diff = 0, bounced_diff = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x)
            for (int c = 0; c < 3; ++c) {
                direct_diff += std::abs(direct0.at(x, y, c) - direct1.at(x, y, c));
                bounced_diff += std::abs(bounced0.at(x, y, c) - bounced1.at(x, y, c));
            }
    EXPECT_EQ(direct_diff, 0.0);
    EXPECT_GT(bounced_diff, 0.0);
}

// Defaults not given scale with the object (FurParams::scale_defaults_to): the same
// sphere at 1/1000 and at 200 times unit size grows the same number of strands, each
// as long relative to the sphere; values given are kept as they are.
TEST(FurRender, UnsetDefaultsScaleWithTheObjectsSize) {
    struct Coat {
        size_t strands;
        double length;  // first strand's root-to-tip distance over the object's radius
    };
    auto coat = [](double scale, const std::string &fur) {
        const std::string scene =
            R"({"camera": {}, "objects": [{"mesh": "procedural:sphere:16x16",
            "transform": {"scale": )" +
            std::to_string(scale) + R"(}, "fur": )" + fur + "}]}";
        const renderer::SceneDesc desc = renderer::parse_scene(scene, "/tmp/s.json");
        const renderer::PluginRegistry plugins;
        const renderer::Scene s(desc, plugins);
        const renderer::Strands &st = s.fur()->layers().at(0).strands;
        const float *p = st.points.data();
        const size_t last = 4 * (st.points_per_strand - 2);  // the tip (no phantom)
        const double dx = p[last] - p[4], dy = p[last + 1] - p[5],
                     dz = p[last + 2] - p[6];
        return Coat{st.size(), std::sqrt(dx * dx + dy * dy + dz * dz) / scale};
    };
    const Coat unit = coat(1, R"({"segments": 4, "length_variation": 0})");
    // The unit sphere (radius 1) has the documented defaults: 20000 strands per unit
    // area over about 4π.
    EXPECT_NEAR(double(unit.strands), 20000 * 4 * 3.14159 * 0.99, 20000 * 0.5);
    for (const double scale : {0.001, 200.0}) {
        const Coat c = coat(scale, R"({"segments": 4, "length_variation": 0})");
        EXPECT_NEAR(double(c.strands), double(unit.strands), 0.01 * unit.strands)
            << scale;
        EXPECT_NEAR(c.length, unit.length, 0.02 * unit.length) << scale;
    }
    // A density given is strands per unit area of the scene, whatever the size.
    const Coat given = coat(10, R"({"segments": 4, "density": 10})");
    EXPECT_NEAR(double(given.strands), 10 * 4 * 3.14159 * 100 * 0.98, 400);
}

// The coat of `colour` ("skin" or "skin_melanin") on two-type cells on an icosphere.
renderer::Scene furry_two_type_scene(TempDir &tmp, const std::string &colour,
                                     const renderer::PluginRegistry &plugins) {
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 400);
    const std::string scene =
        R"({"camera": {}, "objects": [{"mesh": ")" + mesh + R"(", "cells": ")" + cells +
        R"(", "material": {"shader": "clonal_mosaic", "params": {"antialias": 0}},
        "fur": {"density": 800, "length": 0.05, "root_radius": 0.0015, "tip_radius": 0.0003,
                "comb_angle": 30, "melanin_jitter": 0, "segments": 4, "colour": ")" +
        colour + R"("}}]})";
    return renderer::Scene(renderer::parse_scene(scene, tmp.file("scene.json")), plugins);
}

// The skin's own answer at a strand's root.
PelageShade skin_at_root(const renderer::Material &m, const renderer::SurfacePoint &r) {
    PelageHit hit{};
    hit.primitive_id = r.triangle;
    hit.b1 = r.b1;
    hit.b2 = r.b2;
    hit.depth = 1;
    PelageShade sh = pelage_default_shade();
    m.plugin->shade(m.instance, &hit, &sh);
    return sh;
}

TEST(FurRender, EachStrandTakesTheColourTheMosaicShowsAtItsRoot) {
    TempDir tmp;
    const renderer::PluginRegistry plugins;
    const renderer::Scene s = furry_two_type_scene(tmp, "skin", plugins);
    ASSERT_NE(s.fur(), nullptr);
    const renderer::Strands &strands = s.fur()->layers().at(0).strands;
    ASSERT_GT(strands.size(), 1000u);
    // The coat's depth: density × length × (root + tip radius) × cos(comb angle).
    const float depth =
        800 * 0.05f * (0.0015f + 0.0003f) * std::cos(30 * float(M_PI) / 180);
    std::set<std::array<float, 3>> distinct;
    for (size_t i = 0; i < strands.size(); ++i) {
        const PelageShade sh = skin_at_root(s.materials()[0], strands.roots[i]);
        // The inverse of the skin's colour at the default β_n, in the coat as deep as it
        // grows, over that skin (hair_pigments.h).
        const Rgb albedo{sh.albedo[0], sh.albedo[1], sh.albedo[2]};
        const Rgb want = renderer::sigma_a_from_coat_colour(albedo, 0.3f, depth, albedo);
        for (int k = 0; k < 3; ++k)
            ASSERT_NEAR(strands.sigma_a[i][k], want[k], 1e-6f * want[k] + 1e-9f) << i;
        distinct.insert(
            {strands.sigma_a[i].x, strands.sigma_a[i].y, strands.sigma_a[i].z});
    }
    EXPECT_EQ(distinct.size(), 2u);  // one colour per type (no jitter)
}

TEST(FurRender, SkinMelaninTakesTheMosaicsMelaninAtTheRoot) {
    TempDir tmp;
    const renderer::PluginRegistry plugins;
    const renderer::Scene s = furry_two_type_scene(tmp, "skin_melanin", plugins);
    ASSERT_NE(s.fur(), nullptr);
    const renderer::Strands &strands = s.fur()->layers().at(0).strands;
    ASSERT_GT(strands.size(), 1000u);
    size_t dark = 0, light = 0;
    for (size_t i = 0; i < strands.size(); ++i) {
        // The two types of simulate_two_type_cells: F (eumelanin 0.8), B (pheomelanin
        // 0.5), through d'Eon et al.'s absorption (0.419, 0.697, 1.37) and (0.187, 0.4,
        // 1.05).
        const Rgb a = strands.sigma_a[i];
        const bool is_f =
            std::abs(a.x - 0.8f * 0.419f) < 1e-6f && std::abs(a.z - 0.8f * 1.37f) < 1e-6f;
        const bool is_b =
            std::abs(a.x - 0.5f * 0.187f) < 1e-6f && std::abs(a.z - 0.5f * 1.05f) < 1e-6f;
        ASSERT_TRUE(is_f || is_b) << i << ": " << a.x << " " << a.y << " " << a.z;
        (is_f ? dark : light) += 1;
        const PelageShade sh = skin_at_root(s.materials()[0], strands.roots[i]);
        ASSERT_EQ(is_f, sh.eumelanin == 0.8f && sh.pheomelanin == 0.0f);
    }
    EXPECT_GT(dark, strands.size() / 20);
    EXPECT_GT(light, strands.size() / 20);
}

// Strands whose roots are closer than the sum of their radii interpenetrate (at the
// issue's 200 000 strands per unit area and root radius 0.0005, about half of them). A
// ray that leaves one strand inside another must pass out of it: Embree reports the
// inside of a round curve's tube, where the hair BSDF, which models a whole fibre from
// its entry, has no meaning, so fur_geometry.cpp drops those hits (as Cycles does for
// its round curves). A ray from the axis of a lone strand must therefore miss it, and
// the same ray from outside must hit the tube at the radius (so the test can fail).
TEST(FurRender, RaysFromInsideARoundStrandPassOutOfIt) {
    TempDir tmp;
    const float radius = 0.05f;
    const std::string scene =
        R"({"camera": {}, "objects": [{"mesh": "procedural:plane:1x1",
          "transform": {"scale": 0.02},
          "fur": {"density": 600, "length": 1, "length_variation": 0, "root_radius": )" +
        std::to_string(radius) + R"(, "tip_radius": )" + std::to_string(radius) +
        R"(, "segments": 4, "comb": "normal", "comb_jitter": 0, "seed": 1}}]})";
    const renderer::SceneDesc desc = renderer::parse_scene(scene, tmp.file("scene.json"));
    const renderer::PluginRegistry plugins;
    const renderer::Scene s(desc, plugins);
    ASSERT_NE(s.fur(), nullptr);
    const renderer::Strands &strands = s.fur()->layers().at(0).strands;
    ASSERT_EQ(strands.size(), 1u);
    // Control points: a phantom, the root, ..., the tip, a phantom; the middle one lies
    // on the axis, half way up the straight strand.
    const float *mid = &strands.points[4 * size_t(1 + strands.segments / 2)];
    const Vec3f axis_point{mid[0], mid[1], mid[2]};
    const Vec3f across{1, 0, 0};  // ⊥ the strand, which stands on the y-up plane
    auto first_hit = [&](Vec3f o, Vec3f d) {
        RTCRayHit rh;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        renderer::set_ray(rh.ray, o, d, 10);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(s.geometry().scene(), &ctx, &rh);
        return rh;
    };
    const RTCRayHit inside = first_hit(axis_point, across);
    EXPECT_EQ(inside.hit.geomID, RTC_INVALID_GEOMETRY_ID) << "t = " << inside.ray.tfar;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay shadow;
    renderer::set_ray(shadow, axis_point, across, 10);
    rtcOccluded1(s.geometry().scene(), &ctx, &shadow);
    EXPECT_GE(shadow.tfar, 0.0f) << "the shadow ray from inside was blocked";
    const RTCRayHit outside = first_hit(axis_point + across * (2 * radius), -across);
    ASSERT_NE(outside.hit.geomID, RTC_INVALID_GEOMETRY_ID);
    EXPECT_NEAR(outside.ray.tfar, radius, 1e-3f * radius);
}

// A widened strand covers on the image what its fibre does (fur_geometry.cpp): camera
// rays through its axis keep it for a fraction of their stratified numbers equal to its
// opacity, and camera rays that cross its axis past the tip never keep it, though they
// still meet the widened tube's end (each tip once added about a widened radius to the
// strand's length: the silhouette's coverage grew 14 % at one pixel).
TEST(FurRender, AWidenedStrandCoversItsFibreAndEndsAtItsTip) {
    TempDir tmp;
    const std::string scene =
        R"({"camera": {"position": [0, 0.5, 3], "look_at": [0, 0.5, 0]},
          "film": {"width": 64, "height": 64},
          "objects": [{"mesh": "procedural:plane:1x1", "transform": {"scale": 0.02},
          "fur": {"density": 600, "length": 1, "length_variation": 0, "root_radius": 0.004,
          "tip_radius": 0.004, "segments": 4, "comb": "normal", "comb_jitter": 0,
          "seed": 1, "min_pixel_width": 0.5}}]})";
    const renderer::SceneDesc desc = renderer::parse_scene(scene, tmp.file("scene.json"));
    const renderer::PluginRegistry plugins;
    const renderer::Scene s(desc, plugins);
    ASSERT_TRUE(s.fur() && s.fur()->widened());
    const renderer::FurLayer &layer = s.fur()->layers().at(0);
    const renderer::Strands &strands = layer.strands;
    ASSERT_EQ(strands.size(), 1u);
    // Control points: a phantom, the root, ..., the tip, a phantom. The strand stands
    // straight up (+y) on the plane.
    const size_t mid = 1 + size_t(strands.segments / 2),
                 tip = 1 + size_t(strands.segments);
    const Vec3f m{strands.points[4 * mid], strands.points[4 * mid + 1],
                  strands.points[4 * mid + 2]};
    const Vec3f t{strands.points[4 * tip], strands.points[4 * tip + 1],
                  strands.points[4 * tip + 2]};
    const float wide = layer.wide_points[4 * tip + 3];
    ASSERT_GT(wide, 1.5f * 0.004f);
    // The geometry a ray along d with this id, crossing the strand's axis at x, hits:
    // camera rays (fur_ray_id) in the camera scene, the others in the scene.
    auto hit = [&](Vec3f x, Vec3f d, unsigned id) {
        RTCRayHit rh;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        renderer::set_ray(rh.ray, x - d * (4 * wide), d, 10, id);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(id >> 31 ? s.fur()->camera_scene() : s.geometry().scene(), &ctx,
                      &rh);
        return rh.hit.geomID;
    };
    // How many of 32 camera rays (one per stratum of ξ) keep the widened strand.
    auto kept = [&](Vec3f x, Vec3f d) {
        int n = 0;
        for (int q = 0; q < 32; ++q)
            n += hit(x, d, renderer::fur_ray_id(0, (q + 0.5f) / 32)) == layer.geom_id;
        return n;
    };
    const Vec3f up{0, 1, 0}, across{1, 0, 0}, beside{0, 0, 1};
    const float alpha = 0.004f / layer.wide_points[4 * mid + 3];
    ASSERT_GT(alpha, 0.2f);
    EXPECT_NEAR(kept(m, across) / 32.0, alpha, 1.0 / 32 + 1e-6) << "opacity " << alpha;
    // Looking down at 45° onto the tip: a ray crossing the axis 0.3 widened radii past
    // the tip enters the widened tube through its end; one crossing it as far before
    // the tip crosses the fibre.
    const Vec3f down = normalize(Vec3f{1, -1, 0});
    EXPECT_GT(kept(t - up * (0.3f * wide), down), 0);
    EXPECT_EQ(kept(t + up * (0.3f * wide), down), 0);
    EXPECT_EQ(kept(t + up * (0.5f * wide), across), 0);
    // Every other ray sees the fibre alone: it passes half a widened radius beside the
    // axis, hits the fibre through it.
    EXPECT_EQ(hit(m + beside * (0.5f * wide), across, 0), RTC_INVALID_GEOMETRY_ID);
    EXPECT_EQ(hit(m, across, 0), layer.geom_id);
    // The camera scene holds the skin too: straight down onto the plane's corner
    // farthest from the root (at least 0.011 from it, more than the widened radius).
    Vec3f corner{0.008f, 0, 0.008f};
    if (m.x > 0) corner.x = -corner.x;
    if (m.z > 0) corner.z = -corner.z;
    const unsigned skin = hit(corner, {0, -1, 0}, renderer::fur_ray_id(0, 0.5f));
    EXPECT_NE(skin, RTC_INVALID_GEOMETRY_ID);
    EXPECT_NE(skin, layer.geom_id);
}

// The angle (degrees) between a strand's root direction, projected onto the skin's
// tangent plane at the root, and `axis`, folded into [0, 90].
double angle_to_axis(const renderer::Strands &s, size_t i, Vec3f n, Vec3f axis) {
    const float *P = &s.points[4 * i * s.points_per_strand];
    // Round curves: point 0 is a phantom, points 1 and 2 the root and the next.
    const Vec3f a{P[4], P[5], P[6]}, b{P[8], P[9], P[10]};
    Vec3f d = b - a;
    d = d - n * dot(d, n);
    const double c = std::abs(dot(normalize(d), axis));
    return std::acos(std::min(c, 1.0)) * 180 / 3.14159265358979;
}

// A long cylinder along y (radius 0.2, height 2: its principal axis is y), written as
// OBJ; strands with no jitter, gravity or clumping, so each leaves its root along the
// comb.
struct CombCylinder {
    TempDir tmp;
    std::string mesh = tmp.file("cyl.obj");
    CombCylinder() { sim::write_obj(mesh, sim::make_cylinder(48, 12, 0.2, 2.0), {}); }
    renderer::Scene scene(const std::string &comb, const std::string &cells,
                          const renderer::PluginRegistry &plugins) {
        const std::string text =
            R"({"camera": {}, "objects": [{"mesh": ")" + mesh + R"(", )" +
            (cells.empty() ? "" : R"("cells": ")" + cells + R"(", )") +
            R"("material": {"shader": ")" +
            (cells.empty() ? "diffuse" : "clonal_mosaic") +
            R"("}, "fur": {"density": 400, "segments": 4, "comb_jitter": 0, "gravity": 0,
             "comb_angle": 10, "length": 0.05, "comb": )" +
            comb + "}}]}";
        return renderer::Scene(renderer::parse_scene(text, tmp.file("scene.json")),
                               plugins);
    }
};

// The root's outward normal on the cylinder (radial).
Vec3f radial(const renderer::Strands &s, size_t i) {
    const float *P = &s.points[4 * i * s.points_per_strand + 4];
    return normalize(Vec3f{P[0], 0, P[2]});
}

TEST(FurComb, StrandsFollowTheBodyAxisAlongAndAround) {
    CombCylinder c;
    const renderer::PluginRegistry plugins;
    for (const bool around : {false, true}) {
        const renderer::Scene s =
            c.scene(around ? R"({"around": "body_axis"})" : R"({"along": "body_axis"})",
                    "", plugins);
        const renderer::Strands &strands = s.fur()->layers().at(0).strands;
        ASSERT_GT(strands.size(), 500u);
        for (size_t i = 0; i < strands.size(); ++i) {
            const double a = angle_to_axis(strands, i, radial(strands, i), {0, 1, 0});
            // Along: parallel to y; around: perpendicular to it. Within 1°: the test's
            // radial normal is the point's, not the interpolated one the strand used
            // (up to 3.75° apart on 48 sides), which tilts the 10° lift a little.
            ASSERT_LT(around ? 90 - a : a, 1.0) << (around ? "around " : "along ") << i;
        }
        // The sense: along the body axis the hair points down (comb_towards' default);
        // around it, where `towards` says nothing, every strand turns the same way.
        int sense[2] = {0, 0};
        for (size_t i = 0; i < strands.size(); ++i) {
            const float *P = &strands.points[4 * i * strands.points_per_strand];
            const Vec3f d = Vec3f{P[8], P[9], P[10]} - Vec3f{P[4], P[5], P[6]};
            const float s_i =
                around ? dot(d, cross(Vec3f{0, 1, 0}, radial(strands, i))) : -d.y;
            ++sense[s_i > 0];
        }
        EXPECT_EQ(around ? std::min(sense[0], sense[1]) : sense[0], 0)
            << (around ? "around" : "along") << ": " << sense[0] << " / " << sense[1];
    }
    // comb_towards turns an axis field: up instead of down.
    const renderer::Scene up =
        c.scene(R"({"along": "body_axis"}, "comb_towards": [0, 1, 0])", "", plugins);
    const renderer::Strands &su = up.fur()->layers().at(0).strands;
    for (size_t i = 0; i < su.size(); ++i)
        ASSERT_GT(su.points[4 * i * su.points_per_strand + 9],
                  su.points[4 * i * su.points_per_strand + 5])
            << i;
}

// A comb resolved on the rest mesh goes with the skin into a deformed pose: the cylinder
// posed lying along x (each vertex turned 90° about z, a deformation as far as the
// renderer knows), combed along its rest body axis y: the hair lies along x, the posed
// axis, within the same degree as at rest, and points the way the rest's -y went
// (+x). Without carrying, the rest directions in the posed tangent planes run around
// the body.
TEST(FurComb, AFieldCombGoesWithTheSkinIntoADeformedPose) {
    CombCylinder c;
    sim::TriangleMesh pose = sim::make_cylinder(48, 12, 0.2, 2.0);
    for (sim::Vec3d &p : pose.positions) p = sim::Vec3d{-p.y, p.x, p.z};
    const std::string pose_file = c.tmp.file("pose.obj");
    sim::write_obj(pose_file, pose, {});
    const renderer::PluginRegistry plugins;
    const std::string text = R"({"camera": {}, "objects": [{"mesh": ")" + c.mesh +
                             R"(", "deform": ")" + pose_file +
                             R"(", "material": {"shader": "diffuse"},
        "fur": {"density": 400, "segments": 4, "comb_jitter": 0, "gravity": 0,
        "comb_angle": 10, "length": 0.05, "comb": {"along": "body_axis"}}}]})";
    const renderer::Scene s(renderer::parse_scene(text, c.tmp.file("posed.json")),
                            plugins);
    const renderer::Strands &strands = s.fur()->layers().at(0).strands;
    ASSERT_GT(strands.size(), 500u);
    for (size_t i = 0; i < strands.size(); ++i) {
        const float *P = &strands.points[4 * i * strands.points_per_strand + 4];
        const Vec3f n = normalize(Vec3f{0, P[1], P[2]});  // radial about the x axis
        ASSERT_LT(angle_to_axis(strands, i, n, {1, 0, 0}), 1.0) << i;
        ASSERT_GT(P[4] - P[0], 0) << i;  // rest -y turned to +x
    }
}

TEST(FurComb, FieldFollowsThePatternsAnisotropyField) {
    CombCylinder c;
    const renderer::PluginRegistry plugins;
    // A preset whose anisotropy field runs around the body; the fur's "field" reads it
    // from the .cells file.
    std::string preset = slurp(two_type_preset(c.tmp, 200));
    preset.replace(preset.find(R"("relax": "global")"), 17,
                   R"("relax": "global", "w_a": 0.5,
                      "anisotropy": {"field": {"around": "body_axis"}})");
    c.tmp.write("aniso.json", preset);
    const std::string cells = c.tmp.file("a.cells");
    std::string err;
    ASSERT_EQ(run_pelage("sim --mesh " + c.mesh + " --preset " +
                             c.tmp.file("aniso.json") + " -o " + cells,
                         nullptr, &err),
              0)
        << err;
    // The field travels in the file, as the preset gave it.
    EXPECT_EQ(nlohmann::json::parse(sim::read_cells_file(cells).params_json)
                  .at("anisotropy_field"),
              nlohmann::json::parse(R"({"around": "body_axis"})"));
    const renderer::Scene s = c.scene(R"("field")", cells, plugins);
    const renderer::Strands &strands = s.fur()->layers().at(0).strands;
    ASSERT_GT(strands.size(), 500u);
    for (size_t i = 0; i < strands.size(); ++i)
        ASSERT_GT(angle_to_axis(strands, i, radial(strands, i), {0, 1, 0}), 89.0) << i;

    // A pattern without a field: the error names the .cells file and the key.
    const std::string plain = simulate_two_type_cells(c.tmp, c.mesh, 200);
    try {
        c.scene(R"("field")", plain, plugins);
        ADD_FAILURE() << "a pattern without a field was accepted";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("has none"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("fur.comb"), std::string::npos) << e.what();
    }

    // A file from before the field was recorded: grow it again.
    sim::CellsData old = sim::read_cells_file(cells);
    nlohmann::json params = nlohmann::json::parse(old.params_json);
    params.erase("anisotropy_field");
    old.params_json = params.dump();
    const std::string older = c.tmp.file("older.cells");
    sim::write_cells_file(older, old);
    try {
        c.scene(R"("field")", older, plugins);
        ADD_FAILURE() << "a file without the recorded field was accepted";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("pelage sim"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("fur.comb"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace pelage::test
