// The `"fur"` block of a scene object: every key reaches FurParams, defaults stay when a
// key is absent, and bad values name their JSON path (more cases in
// tests/data/bad_scenes/fur_*.json).
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

SceneDesc with_fur(const std::string &fur) {
    return parse_scene(R"({"camera": {}, "objects": [{"mesh": "procedural:icosphere:1"},
        {"mesh": "procedural:icosphere:1", "fur": )" +
                           fur + "}]}",
                       "fur.json");
}

TEST(SceneFur, EveryKeyReachesTheParameters) {
    const SceneDesc s = with_fur(R"({"density": 1234, "density_by_type": [1.5, 0.5],
        "seed": 9, "max_strands": 777777, "length": 0.2, "length_by_type": [1, 2],
        "length_variation": 0.4, "root_radius": 0.01, "tip_radius": 0.002, "segments": 5,
        "comb": [1, 0, 0], "comb_angle": 45, "comb_jitter": 3, "gravity": 0.7,
        "curl_radius": 0.1, "curl_turns": 3, "clump": 0.6, "clump_radius": 0.05,
        "melanin_scale": 2, "melanin_jitter": 0.25, "beta_m": 0.4, "beta_n": 0.5,
        "alpha": -3, "curve": "flat", "melanin": [0.25, 1.5]})");
    ASSERT_FALSE(s.objects[0].fur.has_value());
    ASSERT_TRUE(s.objects[1].fur.has_value());
    const renderer::FurParams &p = *s.objects[1].fur;
    EXPECT_EQ(p.density, 1234);
    EXPECT_EQ(p.vary(FurParams::Groomed::density).by_type,
              (std::vector<float>{1.5f, 0.5f}));
    EXPECT_EQ(p.seed, 9u);
    EXPECT_EQ(p.max_strands, 777777u);
    EXPECT_FLOAT_EQ(p.length, 0.2f);
    EXPECT_EQ(p.vary(FurParams::Groomed::length).by_type, (std::vector<float>{1, 2}));
    EXPECT_FLOAT_EQ(p.length_variation, 0.4f);
    EXPECT_FLOAT_EQ(p.root_radius, 0.01f);
    EXPECT_FLOAT_EQ(p.tip_radius, 0.002f);
    EXPECT_EQ(p.segments, 5);
    EXPECT_EQ(p.comb, renderer::FurParams::Comb::world);
    EXPECT_EQ(p.comb_direction, (Vec3f{1, 0, 0}));
    EXPECT_FLOAT_EQ(p.comb_angle_deg, 45);
    EXPECT_FLOAT_EQ(p.comb_jitter_deg, 3);
    EXPECT_FLOAT_EQ(p.gravity, 0.7f);
    EXPECT_FLOAT_EQ(p.curl_radius, 0.1f);
    EXPECT_FLOAT_EQ(p.curl_turns, 3);
    EXPECT_FLOAT_EQ(p.clump, 0.6f);
    EXPECT_FLOAT_EQ(p.clump_radius, 0.05f);
    EXPECT_FLOAT_EQ(p.melanin_scale, 2);
    EXPECT_FLOAT_EQ(p.melanin_jitter, 0.25f);
    using Kind = renderer::FurParams::Pigment::Kind;
    EXPECT_EQ(p.pigment.kind, Kind::melanin);
    EXPECT_FLOAT_EQ(p.pigment.eumelanin, 0.25f);
    EXPECT_FLOAT_EQ(p.pigment.pheomelanin, 1.5f);
    EXPECT_FLOAT_EQ(p.beta_m, 0.4f);
    EXPECT_FLOAT_EQ(p.beta_n, 0.5f);
    EXPECT_FLOAT_EQ(p.alpha_deg, -3);
    EXPECT_EQ(p.curve, renderer::FurParams::Curve::flat);

    const renderer::FurParams d = *with_fur("{}").objects[1].fur;
    EXPECT_EQ(d.density, renderer::FurParams{}.density);
    EXPECT_EQ(d.curve, renderer::FurParams::Curve::round);
    EXPECT_EQ(d.pigment.kind, Kind::skin);  // the colour the skin shows
    EXPECT_TRUE(d.pigment_by_type.empty());
    // Cycles' melanin 0.8, redness 1: q = ln 5, all pheomelanin, 1.833 q (Cycles'
    // coefficient 0.343 over d'Eon's 0.187 on red).
    const renderer::FurParams c =
        *with_fur(R"({"cycles_melanin": [0.8, 1]})").objects[1].fur;
    EXPECT_EQ(c.pigment.kind, Kind::melanin);
    EXPECT_FLOAT_EQ(c.pigment.eumelanin, 0);
    EXPECT_NEAR(c.pigment.pheomelanin, 0.343 / 0.187 * std::log(5.0), 0.005);
    // A colour for the coat, and per type: a colour, melanins, Cycles' melanins, the
    // skin's colour, the skin's melanins (either spelling of colour).
    const renderer::FurParams h = *with_fur(R"({"color": [0.9, 0.8, 0.6],
        "colour_by_type": [[0.2, 0.1, 0.05], {"melanin": [1, 2]},
                           {"cycles_melanin": [0.8, 1]}, "skin", "skin_melanin"]})")
                                       .objects[1]
                                       .fur;
    EXPECT_EQ(h.pigment.kind, Kind::colour);
    EXPECT_EQ(h.pigment.colour, (Rgb{0.9f, 0.8f, 0.6f}));
    ASSERT_EQ(h.pigment_by_type.size(), 5u);
    EXPECT_EQ(h.pigment_by_type[0].kind, Kind::colour);
    EXPECT_EQ(h.pigment_by_type[0].colour, (Rgb{0.2f, 0.1f, 0.05f}));
    EXPECT_EQ(h.pigment_by_type[1].kind, Kind::melanin);
    EXPECT_FLOAT_EQ(h.pigment_by_type[1].pheomelanin, 2);
    EXPECT_EQ(h.pigment_by_type[2].kind, Kind::melanin);
    EXPECT_NEAR(h.pigment_by_type[2].pheomelanin, c.pigment.pheomelanin, 1e-6);
    EXPECT_EQ(h.pigment_by_type[3].kind, Kind::skin);
    EXPECT_EQ(h.pigment_by_type[4].kind, Kind::skin_melanin);
    EXPECT_EQ(with_fur(R"({"comb": "normal"})").objects[1].fur->comb,
              renderer::FurParams::Comb::normal);
    // A field: the pattern's own, or one given as a preset's anisotropy field.
    const renderer::FurParams f = *with_fur(R"({"comb": "field"})").objects[1].fur;
    EXPECT_EQ(f.comb, renderer::FurParams::Comb::field);
    EXPECT_TRUE(f.comb_pattern_field);
    const renderer::FurParams g =
        *with_fur(R"({"comb": {"around": "body_axis"}})").objects[1].fur;
    EXPECT_EQ(g.comb, renderer::FurParams::Comb::field);
    EXPECT_FALSE(g.comb_pattern_field);
    EXPECT_EQ(g.comb_field.kind, sim::FieldSpec::Kind::around_body_axis);
}

TEST(SceneFur, BadValuesNameTheirJsonPath) {
    const std::pair<const char *, const char *> cases[] = {
        {R"({"segments": 1})", "objects[1].fur.segments"},  // round needs 2
        {R"({"density": -1})", "objects[1].fur.density"},
        {R"({"tip_radius": 0})", "objects[1].fur.tip_radius"},
        {R"({"clump": 1.5})", "objects[1].fur.clump"},
        {R"({"alpha": 60})", "objects[1].fur.alpha"},
        // HairBsdf only DCHECKs its parameters: parsing rejects them
        {R"({"beta_m": 0})", "objects[1].fur.beta_m"},
        {R"({"beta_n": 1.5})", "objects[1].fur.beta_n"},
        {R"({"comb": "up"})", "objects[1].fur.comb"},
        {R"({"comb": [1, "x", 0]})", "objects[1].fur.comb[1]"},
        {R"({"comb": {"along": "tail"}})", "objects[1].fur.comb.along"},
        {R"({"comb": {"along": "body_axis", "around": "body_axis"}})",
         "objects[1].fur.comb"},
        {R"({"density_by_type": [0, 0]})", "objects[1].fur.density_by_type"},
        {R"({"length_by_type": [1, 0]})", "objects[1].fur.length_by_type[1]"},
        {R"({"seed": -4})", "objects[1].fur.seed"},
        {R"({"max_strands": 100000000})", "objects[1].fur.max_strands"},
        {R"({"melanin": [1]})", "objects[1].fur.melanin"},
        {R"({"melanin": [1, -2]})", "objects[1].fur.melanin[1]"},
        {R"({"cycles_melanin": [1, 0]})", "objects[1].fur.cycles_melanin[0]"},
        {R"({"melanin": [0, 1], "cycles_melanin": [0.5, 0]})",
         "objects[1].fur.cycles_melanin"},
        {R"({"colour": [0.5, 0.5, 0.5], "melanin": [0, 1]})", "objects[1].fur.melanin"},
        {R"({"colour": [0.5, 0, 0.5]})", "objects[1].fur.colour[1]"},
        {R"({"color": [0.5, 0.5, 1.5]})", "objects[1].fur.color"},
        {R"({"colour": "fur"})", "objects[1].fur.colour"},
        {R"({"colour_by_type": []})", "objects[1].fur.colour_by_type"},
        {R"({"colour_by_type": [[0.5, 0.5, 0.5], "x"]})",
         "objects[1].fur.colour_by_type[1]"},
        {R"({"colour_by_type": [{"melanin": [1, 1], "cycles_melanin": [0.5, 0]}]})",
         "objects[1].fur.colour_by_type[0]"},
        {R"({"colour_by_type": [{"melanin": [1, -1]}]})",
         "objects[1].fur.colour_by_type[0].melanin[1]"},
        {R"({"colour_by_type": [{"eumelanin": 1}]})",
         "objects[1].fur.colour_by_type[0].eumelanin"},
        {R"({"colour_by_type": [{"sigma_a": [1, 1, -1]}]})",
         "objects[1].fur.colour_by_type[0].sigma_a"},
        // The groom: values by type and by region
        {R"({"beta_m_by_type": [0.3, 0]})", "objects[1].fur.beta_m_by_type[1]"},
        {R"({"comb_angle_by_type": [95]})", "objects[1].fur.comb_angle_by_type[0]"},
        {R"({"root_radius_by_type": [0]})", "objects[1].fur.root_radius_by_type[0]"},
        {R"({"length": {"default": 0.1, "in": {"face": 0.05}}})",
         "objects[1].fur.length"},
        {R"({"regions": {"face": {"near": {"points": [[0, 0, 0]], "within": 0.1}}},
            "length": {"default": 0.1, "in": {"tail": 0.05}}})",
         "objects[1].fur.length.in.tail"},
        {R"({"regions": {"low": {"height": {"axis": [0, 1, 0], "below": 0.3}}},
            "clump": {"default": 0.1, "in": {"low": 2}}})",
         "objects[1].fur.clump.in.low"},
        {R"({"regions": {"low": {"height": {"axis": [0, 1, 0], "below": 0.3}}},
            "length": {"default": 0.1}})",
         "objects[1].fur.length.in"},
        {R"({"regions": {"low": {"hieght": {}}}})", "objects[1].fur.regions.low.hieght"},
        {R"({"regions": {"low": {"any": ["high"]}}})", "objects[1].fur.regions.low.any"},
        {R"({"regions": {"low": {"height": {"axis": [0, 1, 0], "below": 0.3}}},
            "colour": {"default": "skin", "in": {"low": "skin"}}})",
         "objects[1].fur.colour.in.low"},
        {R"({"colour": {"default": "skin", "in": {"low": [1, 1, 1]}}})",
         "objects[1].fur.colour"},
    };
    for (const auto &[fur, field] : cases) {
        try {
            with_fur(fur);
            ADD_FAILURE() << fur << " was accepted";
        } catch (const InputError &e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos)
                << fur << ": " << e.what();
        }
    }
}

// Local values apply their regions in the order the file lists them, as a preset's do.
TEST(SceneFur, AGroomByTypeAndRegionReachesFurParamsInDocumentOrder) {
    using G = renderer::FurParams::Groomed;
    const renderer::FurParams p = *with_fur(R"({
        "regions": {"zz": {"height": {"axis": [0, 1, 0], "below": 0.3}},
                    "aa": {"not": "zz"}},
        "length": {"default": 0.2, "in": {"zz": 0.1, "aa": 0.4}},
        "length_by_type": [1, 2], "beta_n_by_type": [0.2, 0.5],
        "colour": {"default": [0.5, 0.4, 0.3], "in": {"aa": [0.9, 0.9, 0.8]}}})")
                                       .objects[1]
                                       .fur;
    ASSERT_EQ(p.regions.region_names, (std::vector<std::string>{"zz", "aa"}));
    EXPECT_FLOAT_EQ(p.length, 0.2f);
    const auto &in = p.vary(G::length).in;
    ASSERT_EQ(in.size(), 2u);
    EXPECT_EQ(in[0], (std::pair<int, float>{0, 0.1f}));
    EXPECT_EQ(in[1], (std::pair<int, float>{1, 0.4f}));
    EXPECT_EQ(p.vary(G::length).by_type, (std::vector<float>{1, 2}));
    EXPECT_EQ(p.vary(G::beta_n).by_type, (std::vector<float>{0.2f, 0.5f}));
    EXPECT_FALSE(p.vary(G::density).varies());
    EXPECT_EQ(p.pigment.kind, renderer::FurParams::Pigment::Kind::colour);
    ASSERT_EQ(p.colour_in.size(), 1u);
    EXPECT_EQ(p.colour_in[0].first, 1);
}

// The regions are resolved on the object's surface as a preset's are: below half the
// sphere's height the hair is short, above it long (blending over the triangles that
// straddle the line, within an edge of it: icosphere:3 edges are about 0.2 long).
TEST(SceneFur, RegionsAreResolvedOnTheObjectsSurface) {
    const SceneDesc desc = parse_scene(
        R"({"camera": {}, "objects": [{"mesh": "procedural:icosphere:3",
            "transform": {"translate": [0, 5, 0]},
            "fur": {"density": 3000, "length_variation": 0, "curve": "flat",
                    "regions": {"low": {"height": {"axis": [0, 1, 0], "below": 0.5}}},
                    "length": {"default": 0.3, "in": {"low": 0.1}}}}]})",
        "fur.json");
    const PluginRegistry plugins;
    const Scene scene(desc, plugins);
    ASSERT_TRUE(scene.fur());
    const Strands &s = scene.fur()->layers().at(0).strands;
    size_t low = 0, high = 0;
    for (size_t i = 0; i < s.size(); ++i) {
        const float *P = &s.points[i * s.points_per_strand * 4];
        const float *T = P + 4 * s.segments;
        // Straight (no gravity, no curl): the length is root to tip.
        const float L =
            std::sqrt((T[0] - P[0]) * (T[0] - P[0]) + (T[1] - P[1]) * (T[1] - P[1]) +
                      (T[2] - P[2]) * (T[2] - P[2]));
        const float y = P[1] - 5;  // the translation moves the sphere, not its regions
        if (y < -0.25f) {
            EXPECT_NEAR(L, 0.1f, 1e-4f) << y;
            ++low;
        }
        if (y > 0.25f) {
            EXPECT_NEAR(L, 0.3f, 1e-4f) << y;
            ++high;
        }
    }
    EXPECT_GT(low, 1000u);
    EXPECT_GT(high, 1000u);
}

// HairBsdf only DCHECKs its parameters at each strand hit, so the scene build validates
// them once per fur layer: 1e-50 passes the parser's (0, 1] as a double but is 0 as the
// float the BSDF takes.
TEST(SceneFur, HairParametersAreValidatedOncePerLayer) {
    const SceneDesc desc = with_fur(R"({"density": 10, "beta_m": 1e-50})");
    const PluginRegistry plugins;
    try {
        const Scene s(desc, plugins);
        ADD_FAILURE() << "beta_m = 1e-50 was accepted";
    } catch (const InputError &e) {
        EXPECT_NE(std::string(e.what()).find("beta_m = 0"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace pelage::renderer
