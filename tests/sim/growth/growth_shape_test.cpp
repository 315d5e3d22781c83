// The growth block of a preset: parser errors name the JSON path; the shape at an age
// against hand-computed positions (linear and smooth interpolation, Walter's cylinders
// with blending and a parent's pivot), and mesh keys moved onto a simplified copy.
#include "sim/growth/growth_shape.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sim/core/input_error.h"
#include "sim/mesh/closest_point.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mesh/procedural_mesh.h"
#include "sim/mosaic/preset.h"
#include "tests/sim/sim_test_util.h"
#include "tests/test_paths.h"

namespace pelage::sim {
namespace {

void expect_near(Vec3d a, Vec3d b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

GrowthSpec parse(const std::string &text, const std::string &base = "") {
    return parse_growth(nlohmann::json::parse(text), "growth", "p.json", base);
}

// The error of parsing `text`: "field: message" of the InputError.
std::string error_of(const std::string &text) {
    try {
        parse(text);
    } catch (const InputError &e) {
        return e.field() + ": " + e.what();
    }
    return "no error";
}

TEST(GrowthSpec, ParsesKeysCylindersAndInterpolation) {
    const GrowthSpec s = parse(R"({
      "interpolation": "smooth", "interval": 0.5,
      "cylinders": [{"name": "body", "from": [0,0,0], "to": [2,0,0], "radius": 1},
                    {"name": "leg", "from": [1,0,0], "to": [1,-2,0], "radius": 0.5,
                     "parent": "body"}],
      "keys": [{"age": 0, "scale": 0.5}, {"age": 3, "mesh": "calf.obj"},
               {"age": 9, "cylinders": {"leg": {"length": 2}}}]})",
                               "/presets");
    EXPECT_EQ(s.interpolation, GrowthInterpolation::smooth);
    EXPECT_EQ(s.interval, 0.5);
    ASSERT_EQ(s.cylinders.size(), 2u);
    EXPECT_EQ(s.cylinders[1].parent, 0);
    ASSERT_EQ(s.keys.size(), 3u);
    EXPECT_EQ(s.keys[0].scale, 0.5);
    EXPECT_EQ(s.keys[1].mesh, "/presets/calf.obj");
    EXPECT_TRUE(s.has_mesh_keys());
    // A cylinder a key does not name keeps its rest size; an omitted scale is 1.
    EXPECT_EQ(s.keys[2].cylinder_scales[0], (std::array<double, 2>{1, 1}));
    EXPECT_EQ(s.keys[2].cylinder_scales[1], (std::array<double, 2>{2, 1}));
}

TEST(GrowthSpec, ErrorsNameTheJsonPath) {
    const std::string cyl =
        R"("cylinders": [{"name": "a", "from": [0,0,0], "to": [1,0,0], "radius": 1}], )";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({})", "growth.keys: "},
        {R"({"keys": []})", "growth.keys: "},
        {R"({"keys": [{"age": 0}]})", "growth.keys[0]: "},
        {R"({"keys": [{"age": 0, "scale": 1, "mesh": "a.obj"}]})", "growth.keys[0]: "},
        {R"({"keys": [{"scale": 1}]})", "growth.keys[0].age: "},
        {R"({"keys": [{"age": 0, "scale": -1}]})", "growth.keys[0].scale: "},
        {R"({"keys": [{"age": 1, "scale": 1}, {"age": 1, "scale": 2}]})",
         "growth.keys[1].age: "},
        {R"({"keys": [{"age": 0, "scale": 1, "size": 2}]})", "growth.keys[0].size: "},
        {R"({"keys": [{"age": 0, "scale": 1}], "interpolation": "cubic"})",
         "growth.interpolation: "},
        {R"({"keys": [{"age": 0, "scale": 1}], "interval": 0})", "growth.interval: "},
        {R"({"keys": [{"age": 0, "cylinders": {"a": {"length": 2}}}]})",
         "growth.keys[0].cylinders: "},
        {"{" + cyl + R"("keys": [{"age": 0, "cylinders": {"b": {"length": 2}}}]})",
         "growth.keys[0].cylinders.b: "},
        {"{" + cyl + R"("keys": [{"age": 0, "cylinders": {"a": {"length": 0}}}]})",
         "growth.keys[0].cylinders.a.length: "},
        {R"({"cylinders": [{"name": "a", "from": [0,0,0], "to": [0,0,0], "radius": 1}],
            "keys": [{"age": 0, "scale": 1}]})",
         "growth.cylinders[0].to: "},
        {R"({"cylinders": [{"name": "a", "from": [0,0,0], "to": [1,0,0], "radius": 1,
            "parent": "b"}], "keys": [{"age": 0, "scale": 1}]})",
         "growth.cylinders[0].parent: "},
    };
    for (const auto &[text, field] : cases)
        EXPECT_EQ(error_of(text).rfind(field, 0), 0u) << text << " -> " << error_of(text);
}

TEST(GrowthSpec, APresetCarriesItsGrowthBlock) {
    const std::string base = test::preset_json(
        R"({"initial_cells": 10, "w_r": 2, "w_d": 0.1, "rho": 1, "end_time": 1})");
    const std::string with = base.substr(0, base.size() - 1) +
                             R"(, "growth": {"keys": [{"age": 0, "scale": 2}]}})";
    const Preset p = parse_preset(with, "/somewhere/p.json");
    ASSERT_TRUE(p.growth.has_value());
    EXPECT_EQ(p.growth->keys[0].scale, 2);
    EXPECT_FALSE(parse_preset(base, "p.json").growth.has_value());
    try {
        parse_preset(base.substr(0, base.size() - 1) + R"(, "growth": {"keys": 3}})",
                     "p.json");
        FAIL();
    } catch (const InputError &e) {
        EXPECT_EQ(e.field(), "growth.keys");
        EXPECT_EQ(e.file(), "p.json");
    }
}

TEST(GrowthShape, LinearAndSmoothAgainstHandComputedPositions) {
    // One vertex at (0,0,0) at age 0, (2,0,0) at 2, (2,4,0) at 6.
    const std::vector<double> ages{0, 2, 6};
    const std::vector<std::vector<Vec3d>> keys{{{0, 0, 0}}, {{2, 0, 0}}, {{2, 4, 0}}};
    const GrowthShape lin(ages, keys, GrowthInterpolation::linear, 1);
    expect_near(lin.at(-1)[0], {0, 0, 0});  // before the first key: the first
    expect_near(lin.at(1)[0], {1, 0, 0});
    expect_near(lin.at(2)[0], {2, 0, 0});
    expect_near(lin.at(4)[0], {2, 2, 0});
    expect_near(lin.at(9)[0], {2, 4, 0});  // after the last: the last
    // Smooth at age 1: s = 1/2, h = 2, m0 = (P1 − P0)/2 = (1,0,0) (one-sided),
    // m1 = (P2 − P0)/6 = (1/3, 2/3, 0); Hermite basis (1/2, 1/8, 1/2, −1/8):
    // P = P0/2 + 2·m0/8 + P1/2 − 2·m1/8 = (1.25 − 1/12, −1/6, 0).
    const GrowthShape smooth(ages, keys, GrowthInterpolation::smooth, 1);
    expect_near(smooth.at(1)[0], {1.25 - 1.0 / 12, -1.0 / 6, 0});
    expect_near(smooth.at(2)[0], {2, 0, 0});  // through every key
    // Age 4 (s = 1/2, h = 4): m1 = (1/3, 2/3, 0), m2 = (P2 − P1)/4 = (0, 1, 0)
    // (one-sided): P = P1/2 + 4·m1/8 + P2/2 − 4·m2/8 = (2 + 1/6, 2 + 1/3 − 1/2, 0).
    expect_near(smooth.at(4)[0], {2 + 1.0 / 6, 2 + 1.0 / 3 - 0.5, 0});
    // Two keys: the straight line.
    const GrowthShape two({0, 4}, {{{0, 0, 0}}, {{4, 8, 0}}}, GrowthInterpolation::smooth,
                          1);
    expect_near(two.at(1)[0], {1, 2, 0});
}

TEST(GrowthShape, CylindersScaleAboutTheirPivotAndBlendByDistanceToTheAxis) {
    std::vector<GrowthCylinder> c(1);
    c[0] = {"a", {0, 0, 0}, {2, 0, 0}, 1.0, -1};
    // Alone: axial coordinate × L, radial offset × R.
    expect_near(grow_by_cylinders(c, {{3, 0.5}}, {1, 0.4, 0}), {3, 0.2, 0});
    // Outside every cylinder: unchanged (thesis L1352).
    expect_near(grow_by_cylinders(c, {{3, 0.5}}, {2.5, 0, 0}), {2.5, 0, 0});
    expect_near(grow_by_cylinders(c, {{3, 0.5}}, {1, 1.5, 0}), {1, 1.5, 0});
    // B (radius 2) is A's child from (1,0,0) to (3,0,0); A doubles its length.
    c.push_back({"b", {1, 0, 0}, {3, 0, 0}, 2.0, 0});
    // p = (1.5, 0.5, 0): A alone gives (3, 0.5, 0) with weight 1 − 0.5; B's pivot moves
    // with A to (2,0,0) and B alone gives (2.5, 0.5, 0) with weight 1 − 0.25.
    // x = (3·0.5 + 2.5·0.75) / 1.25 = 2.7.
    expect_near(grow_by_cylinders(c, {{2, 1}, {1, 1}}, {1.5, 0.5, 0}), {2.7, 0.5, 0});
    // Vertices in no cylinder are counted.
    TriangleMesh m;
    m.positions = {{1, 0.5, 0}, {2.5, 1.5, 0}, {3.5, 0, 0}, {-0.5, 0, 0}};
    EXPECT_EQ(vertices_outside_cylinders(c, m), 2u);  // (3.5,0,0) and (-0.5,0,0)
    // Only in B: its pivot moved by A, its own scales.
    expect_near(grow_by_cylinders(c, {{2, 1}, {1.5, 2}}, {2.8, 1.2, 0}),
                {2 + 1.5 * 1.8, 2.4, 0});
}

TEST(GrowthShape, ScaleKeysAboutTheAreaCentroid) {
    TriangleMesh m = make_uv_sphere(8, 12, 1.0);
    for (Vec3d &p : m.positions) p += Vec3d{1, 2, 3};
    GrowthSpec spec =
        parse(R"({"keys": [{"age": 0, "scale": 0.5}, {"age": 4, "scale": 2}]})");
    const GrowthShape shape = resolve_growth(spec, m, m);
    const Vec3d c = area_centroid(m);
    expect_near(c, {1, 2, 3}, 1e-12);
    const std::vector<Vec3d> at2 = shape.at(2);  // scale 1.25
    for (size_t v = 0; v < m.num_vertices(); ++v)
        expect_near(at2[v], c + (m.positions[v] - c) * 1.25, 1e-12);
}

TEST(GrowthShape, MeshKeysCheckTheTopologyAndMoveASimplifiedCopy) {
    test::TempDir tmp;
    // Both through the loader, as the CLI reads them.
    write_obj(tmp.file("rest.obj"), make_uv_sphere(10, 16, 1.0), {});
    const TriangleMesh rest = load_mesh(tmp.file("rest.obj"));
    // The key: the rest sphere stretched ×2 along x.
    TriangleMesh key = rest;
    for (Vec3d &p : key.positions) p.x *= 2;
    write_obj(tmp.file("key.obj"), key, {});
    GrowthSpec spec =
        parse(R"({"keys": [{"age": 0, "mesh": "key.obj"}]})", tmp.path().string());
    const std::vector<Vec3d> on_rest = key_positions(spec, 0, rest);
    for (size_t v = 0; v < rest.num_vertices(); ++v)
        expect_near(on_rest[v], key.positions[v], 1e-6);  // as written in OBJ text
    // A copy whose vertices lie on the rest triangles (their centroids): each moves by
    // the displacement of its closest point, here its triangle's centroid's.
    TriangleMesh copy;
    for (TriId t = 0; t < rest.num_triangles(); ++t)
        copy.positions.push_back(
            (rest.vertex(t, 0) + rest.vertex(t, 1) + rest.vertex(t, 2)) / 3.0);
    copy.triangles = {{0, 1, 2}};
    const GrowthShape shape = resolve_growth(spec, rest, copy);
    const std::vector<Vec3d> moved = shape.at(0);
    for (size_t v = 0; v < copy.num_vertices(); ++v)
        expect_near(moved[v],
                    {2 * copy.positions[v].x, copy.positions[v].y, copy.positions[v].z},
                    1e-6);
    // Another topology: named clearly.
    write_obj(tmp.file("other.obj"), make_uv_sphere(10, 17, 1.0), {});
    spec = parse(R"({"keys": [{"age": 0, "scale": 1}, {"age": 1, "mesh": "other.obj"}]})",
                 tmp.path().string());
    try {
        key_positions(spec, 1, rest);
        FAIL();
    } catch (const InputError &e) {
        EXPECT_EQ(e.field(), "growth.keys[1].mesh");
        EXPECT_NE(std::string(e.what()).find("does not have the rest mesh's topology"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GrowthShape, ClosestPointsAgainstBruteForce) {
    const TriangleMesh m = make_uv_sphere(12, 20, 1.0);
    std::vector<Vec3d> points;
    for (int i = 0; i < 200; ++i) {
        const double a = 0.37 * i, b = 0.11 * i;
        const double r = 0.5 + 0.01 * (i % 100);
        points.push_back({r * std::cos(a) * std::cos(b), r * std::sin(b),
                          r * std::sin(a) * std::cos(b)});
    }
    const std::vector<MeshPoint> found =
        closest_points(m, points, RankBy::barycentric_blend);  // as the growth ranks
    for (size_t i = 0; i < points.size(); ++i) {
        double best = 1e300;
        for (TriId t = 0; t < m.num_triangles(); ++t) {
            // Dense barycentric sampling is an upper bound; the answer must not exceed
            // it.
            for (int u = 0; u <= 20; ++u)
                for (int v = 0; u + v <= 20; ++v) {
                    const Vec3d q = m.vertex(t, 0) * ((20.0 - u - v) / 20) +
                                    m.vertex(t, 1) * (u / 20.0) +
                                    m.vertex(t, 2) * (v / 20.0);
                    best = std::min(best, length(q - points[i]));
                }
        }
        const MeshPoint &f = found[i];
        const Vec3d q = m.vertex(f.tri, 0) * f.bary.x + m.vertex(f.tri, 1) * f.bary.y +
                        m.vertex(f.tri, 2) * f.bary.z;
        EXPECT_LE(length(q - points[i]), best + 1e-12) << i;
    }
}

}  // namespace
}  // namespace pelage::sim
