// The clonal_mosaic plugin through the plugin ABI, as the renderer calls it: colours and
// AOVs equal a direct closest-cell lookup, soft boundaries are continuous, bad inputs are
// refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "pattern/mosaic/closest_cell.h"
#include "pattern/mosaic/mosaic_lod.h"
#include "pattern/mosaic/pattern.h"
#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"
#include "sim/mesh/subdivide.h"
#include "tests/pattern/transfer/triangle_soup.h"
#include "tests/shader/clonal_mosaic/mosaic_plugin_instance.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const std::string mesh_spec = "procedural:icosphere:3";

// The plugin on `mesh_path` (the icosphere unless given).
struct Instance : MosaicPluginInstance {
    Instance(const nlohmann::json &p, const char *cells,
             const std::string &mesh_path = mesh_spec)
        : MosaicPluginInstance(p, cells, mesh_path) {}
};

// The cells of a .cells file as the search's table: the reference the plugin is checked
// against, built without the plugin.
pattern::mosaic::CellTable table_of(const sim::CellsData &data) {
    std::vector<pattern::mosaic::CellOnSurface> list;
    for (sim::TriId t = 0; t < data.num_triangles(); ++t)
        for (uint32_t k = data.cell_row[t]; k < data.cell_row[t + 1]; ++k)
            list.push_back({t, data.x[k], data.z[k], data.id[k], data.type[k]});
    return pattern::mosaic::make_cell_table(data.num_triangles(), list);
}

// ABI 3: the plugin builds its surface from the renderer's mesh view; the mesh file is
// never opened (its name is for messages only), and the pattern is the one the file's
// own loading gives.
TEST(ClonalMosaicPlugin, BuildsFromTheMeshViewWithoutOpeningTheMeshFile) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 300);
    const Instance reference({{"antialias", 0}}, cells.c_str());
    ASSERT_NE(reference.self, nullptr) << reference.error;

    const MosaicPluginInstance inst({{"antialias", 0}}, cells.c_str(), mesh_spec,
                                    tmp.file("no/such/mesh.off"));
    ASSERT_NE(inst.self, nullptr) << inst.error;
    for (uint32_t prim = 0; prim < inst.mesh.num_triangles(); prim += 7) {
        const PelageShade sh = inst.shade(prim, 0.3f, 0.3f);
        const PelageShade expected = reference.shade(prim, 0.3f, 0.3f);
        ASSERT_EQ(sh.aov[0], expected.aov[0]) << prim;
        ASSERT_EQ(sh.cell_type, expected.cell_type) << prim;
    }
}

TEST(ClonalMosaicPlugin, ColourAndAovsAreTheNearestCellsType) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const Instance inst({{"antialias", 0}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;

    // The reference: the same search built directly from the .cells file.
    const sim::CellsData data = sim::read_cells_file(cells);
    const sim::Surface s = sim::build_surface(mesh_spec);
    const pattern::mosaic::CellTable table = table_of(data);
    const pattern::mosaic::ClosestCellIndex index(s.crps, table);

    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0, 1);
    for (int n = 0; n < 5000; ++n) {
        const uint32_t prim = rng() % s.mesh.num_triangles();
        float b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        const PelageShade sh = inst.shade(prim, b1, b2);
        const sim::Vec2d q = s.crps.barycentric_to_2d(prim, {1 - b1 - b2, b1, b2});
        const pattern::mosaic::ClosestCell c =
            index.find_nearest(prim, {float(q.x), float(q.y)});
        ASSERT_EQ(sh.aov_written, 1u);
        ASSERT_EQ(uint32_t(sh.aov[0]), table.id[c.index]);
        const sim::CellsFileType &type = data.types[table.type[c.index]];
        ASSERT_EQ(sh.aov[1], float(table.type[c.index]));
        ASSERT_EQ(sh.cell_type, int32_t(table.type[c.index]));
        for (int k = 0; k < 3; ++k) ASSERT_FLOAT_EQ(sh.albedo[k], type.colour[k]);
        ASSERT_FLOAT_EQ(sh.eumelanin, type.eumelanin);
        ASSERT_NEAR(sh.aov[2], c.f1, 1e-6);
    }
}

// Soft edges: the albedo is the blend of the cells within F1 + 2w with weights
// 1 - smoothstep(0, 2w, F_i - F1), and a hit with no other cell that close takes the
// nearest cell's colour exactly (the plugin's shortcut for that case); AOVs name the
// nearest cell either way. Both cases must occur.
TEST(ClonalMosaicPlugin, SoftEdgeColourIsTheBlendOfTheCellsWithinTheBand) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const float w = 0.01f;
    const Instance inst({{"antialias", 0}, {"edge_width", w}, {"jitter", 0.3}},
                        cells.c_str());
    const Instance hard({{"antialias", 0}, {"jitter", 0.3}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;

    const sim::CellsData data = sim::read_cells_file(cells);
    const sim::Surface s = sim::build_surface(mesh_spec);
    const pattern::mosaic::CellTable table = table_of(data);
    const pattern::mosaic::ClosestCellIndex index(s.crps, table);

    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0, 1);
    int single = 0, blended = 0;
    for (int n = 0; n < 5000; ++n) {
        const uint32_t prim = rng() % s.mesh.num_triangles();
        float b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        const PelageShade soft = inst.shade(prim, b1, b2);
        const auto near = index.find_three_within(prim, b1, b2, 2 * w);
        ASSERT_NE(near.index[0], pattern::mosaic::ClosestCell::none);
        ASSERT_EQ(uint32_t(soft.aov[0]), table.id[near.index[0]]);
        ASSERT_EQ(soft.aov[2], std::sqrt(near.d2[0]));
        if (near.index[1] == pattern::mosaic::ClosestCell::none) {
            // Exactly the hard-edged colour: same nearest cell, same jittered look.
            const PelageShade h = hard.shade(prim, b1, b2);
            for (int k = 0; k < 3; ++k) ASSERT_EQ(soft.albedo[k], h.albedo[k]);
            ASSERT_EQ(soft.eumelanin, h.eumelanin);
            ++single;
            continue;
        }
        // The reference blend, from each cell's own hard-edged colour (a point at the
        // cell's centre is coloured by that cell alone).
        const float f1 = std::sqrt(near.d2[0]);
        float rgb[3] = {0, 0, 0}, total = 0;
        for (int i = 0; i < 3 && near.index[i] != pattern::mosaic::ClosestCell::none;
             ++i) {
            const float x = std::min((std::sqrt(near.d2[i]) - f1) / (2 * w), 1.0f);
            const float weight = 1 - x * x * (3 - 2 * x);
            const uint32_t c = near.index[i];
            uint32_t tri = 0;
            while (table.row[tri + 1] <= c) ++tri;
            const sim::Vec3d bary = s.crps.to_barycentric(tri, {table.x[c], table.z[c]});
            const PelageShade at_centre = hard.shade(tri, float(bary.y), float(bary.z));
            ASSERT_EQ(uint32_t(at_centre.aov[0]), table.id[c]);
            for (int k = 0; k < 3; ++k) rgb[k] += weight * at_centre.albedo[k];
            total += weight;
        }
        for (int k = 0; k < 3; ++k) ASSERT_NEAR(soft.albedo[k], rgb[k] / total, 1e-5f);
        ++blended;
    }
    EXPECT_GT(single, 500);
    EXPECT_GT(blended, 500);
}

// With a soft width, walking across the surface never jumps in colour; without it, the
// walk crosses hard boundaries. The blend uses the three nearest cells, so it is
// continuous unless four cells lie within 2w of each other's distance; with w a few
// percent of the cell spacing (0.14 here), as for antialiasing, that does not happen.
TEST(ClonalMosaicPlugin, SoftBoundariesAreContinuous) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const Instance hard({{"antialias", 0}}, cells.c_str());
    const Instance soft({{"antialias", 0}, {"edge_width", 0.005}}, cells.c_str());
    ASSERT_NE(soft.self, nullptr) << soft.error;
    float max_jump_hard = 0, max_jump_soft = 0;
    for (uint32_t prim = 0; prim < 1280; prim += 7) {
        PelageShade prev_h = hard.shade(prim, 0.0f, 0.0f),
                    prev_s = soft.shade(prim, 0.0f, 0.0f);
        for (int k = 1; k <= 400; ++k) {  // corner 0 to the middle of edge 1-2
            const float t = k / 400.0f;
            const PelageShade h = hard.shade(prim, 0.5f * t, 0.5f * t),
                              s = soft.shade(prim, 0.5f * t, 0.5f * t);
            max_jump_hard =
                std::max(max_jump_hard, std::abs(h.albedo[0] - prev_h.albedo[0]));
            max_jump_soft =
                std::max(max_jump_soft, std::abs(s.albedo[0] - prev_s.albedo[0]));
            prev_h = h;
            prev_s = s;
        }
    }
    EXPECT_GT(max_jump_hard, 0.7f);  // F and B differ by 0.8 in red
    EXPECT_LT(max_jump_soft, 0.1f);
}

// Reusing the previous hit's cell (coherence, on by default) must never change a result:
// walks of tiny steps across every triangle, crossing many cell boundaries, with soft
// edges and varying footprints, give bit-identical outputs with and without it (with
// it, shade() answers reused camera hits on a path of its own). (Each
// instance walks on its own: they share the thread's reuse slot.)
TEST(ClonalMosaicPlugin, ReusingThePreviousCellGivesTheSameResultsAsSearching) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    auto walk = [&](int coherence) {
        const Instance inst({{"edge_width", 0.002}, {"coherence", coherence}},
                            cells.c_str());
        EXPECT_NE(inst.self, nullptr) << inst.error;
        std::vector<PelageShade> out;
        for (uint32_t prim = 0; prim < 1280; prim += 3)
            for (int k = 0; k <= 300; ++k) {  // corner 0 to the middle of edge 1-2
                const float t = k / 300.0f;
                // 0, 1e-3, 2e-3, and 0.15: past the triangles' size (~0.1), where the
                // level of detail's ramp takes over (the plugin's fast path must not).
                const float footprints[] = {0, 0.001f, 0.002f, 0.15f};
                const float footprint = footprints[(k / 50) % 4];
                out.push_back(
                    inst.shade(prim, 0.5f * t, 0.5f * t + 0.1f * t * (1 - t), footprint));
            }
        return out;
    };
    const std::vector<PelageShade> reused = walk(1), searched = walk(0);
    ASSERT_EQ(reused.size(), searched.size());
    size_t same_cell_as_before = 0, boundaries = 0;
    for (size_t i = 0; i < reused.size(); ++i) {
        ASSERT_EQ(std::memcmp(&reused[i], &searched[i], sizeof(PelageShade)), 0) << i;
        if (i == 0) continue;
        if (searched[i].aov[0] == searched[i - 1].aov[0])
            ++same_cell_as_before;
        else
            ++boundaries;
    }
    // The walks exercise both: long runs inside cells (where reuse applies) and
    // crossings.
    EXPECT_GT(same_cell_as_before, reused.size() / 2);
    EXPECT_GT(boundaries, 500u);
}

TEST(ClonalMosaicPlugin, RefusesMissingCellsWrongMeshAndBadParameters) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const Instance no_cells({}, nullptr);
    EXPECT_EQ(no_cells.self, nullptr);
    EXPECT_NE(no_cells.error.find("cells"), std::string::npos) << no_cells.error;
    // Another shape: a torus for cells grown on a sphere (another tessellation of the
    // sphere would be taken, through closest points: surface_transfer_test.cpp).
    const Instance wrong_mesh({}, cells.c_str(), "procedural:torus:24x12");
    EXPECT_EQ(wrong_mesh.self, nullptr);
    EXPECT_NE(wrong_mesh.error.find("another surface"), std::string::npos)
        << wrong_mesh.error;
    const Instance bad_rough({{"roughness", "Q=0.3"}}, cells.c_str());
    EXPECT_EQ(bad_rough.self, nullptr);
    EXPECT_NE(bad_rough.error.find("\"Q\""), std::string::npos) << bad_rough.error;
    const Instance missing_file({}, tmp.file("nope.cells").c_str());
    EXPECT_EQ(missing_file.self, nullptr);
    EXPECT_NE(missing_file.error.find("nope.cells"), std::string::npos)
        << missing_file.error;
}

TEST(ClonalMosaicPlugin, PerTypeRoughnessOverridesTheMaterial) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const Instance inst({{"antialias", 0}, {"roughness", "F=0.25"}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;
    int f = 0, b = 0;
    for (uint32_t prim = 0; prim < 1280; ++prim) {
        const PelageShade sh = inst.shade(prim, 0.3f, 0.3f);
        if (sh.aov[1] == 0.0f) {
            EXPECT_FLOAT_EQ(sh.roughness, 0.25f);
            ++f;
        } else {
            EXPECT_FLOAT_EQ(sh.roughness, -1.0f);
            ++b;
        }
    }
    EXPECT_GT(f, 50);
    EXPECT_GT(b, 50);
}

TEST(ClonalMosaicPlugin, PerTypeSpecularSetsTheCoatIor) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    // F0 0.04 is a coat of ior 1.5; B keeps the material's (0: no override).
    const Instance inst({{"antialias", 0}, {"specular", "F=0.04"}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;
    int f = 0, b = 0;
    for (uint32_t prim = 0; prim < 1280; ++prim) {
        const PelageShade sh = inst.shade(prim, 0.3f, 0.3f);
        if (sh.aov[1] == 0.0f) {
            EXPECT_NEAR(sh.ior, 1.5f, 1e-5f);
            ++f;
        } else {
            EXPECT_EQ(sh.ior, 0.0f);
            ++b;
        }
    }
    EXPECT_GT(f, 50);
    EXPECT_GT(b, 50);
    const Instance none({{"antialias", 0}, {"specular", "F=0,B=0.25"}}, cells.c_str());
    ASSERT_NE(none.self, nullptr) << none.error;
    for (uint32_t prim = 0; prim < 1280; ++prim) {
        const PelageShade sh = none.shade(prim, 0.3f, 0.3f);
        EXPECT_NEAR(sh.ior, sh.aov[1] == 0.0f ? 1.0f : 3.0f, 1e-5f);
    }
    for (const char *bad : {"F=0.3", "F=-0.01", "Q=0.04", "F0.04", "F="}) {
        const Instance refused({{"specular", bad}}, cells.c_str());
        EXPECT_EQ(refused.self, nullptr) << bad;
        EXPECT_NE(refused.error.find("specular"), std::string::npos) << refused.error;
    }
}

// A scene's "types" restyles a pattern without simulating again: each listed key
// replaces the .cells file's value for that type, the other type is untouched, and
// mistakes name their field.
TEST(ClonalMosaicPlugin, TypesOverrideColourPigmentsRoughnessAndSpecular) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const nlohmann::json types = {{"F",
                                   {{"colour", {0.7, 0.2, 0.1}},
                                    {"eumelanin", 0.1},
                                    {"pheomelanin", 2.5},
                                    {"roughness", 0.6},
                                    {"specular", 0.04}}}};
    // As the scene file gives it: an object where the table says string.
    const Instance inst({{"antialias", 0}, {"types", types}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;
    int f = 0, b = 0;
    for (uint32_t prim = 0; prim < 1280; ++prim) {
        const PelageShade sh = inst.shade(prim, 0.3f, 0.3f);
        if (sh.aov[1] == 0.0f) {
            EXPECT_FLOAT_EQ(sh.albedo[0], 0.7f);
            EXPECT_FLOAT_EQ(sh.albedo[1], 0.2f);
            EXPECT_FLOAT_EQ(sh.albedo[2], 0.1f);
            EXPECT_FLOAT_EQ(sh.eumelanin, 0.1f);
            EXPECT_FLOAT_EQ(sh.pheomelanin, 2.5f);
            EXPECT_FLOAT_EQ(sh.roughness, 0.6f);
            EXPECT_NEAR(sh.ior, 1.5f, 1e-5f);
            ++f;
        } else {
            // B as simulate_two_type_cells made it (test_paths.h).
            EXPECT_FLOAT_EQ(sh.albedo[0], 0.9f);
            EXPECT_FLOAT_EQ(sh.albedo[1], 0.6f);
            EXPECT_FLOAT_EQ(sh.albedo[2], 0.3f);
            EXPECT_FLOAT_EQ(sh.pheomelanin, 0.5f);
            EXPECT_FLOAT_EQ(sh.roughness, -1.0f);
            EXPECT_EQ(sh.ior, 0.0f);
            ++b;
        }
    }
    EXPECT_GT(f, 50);
    EXPECT_GT(b, 50);
    // "color" is accepted too.
    const Instance us({{"types", {{"B", {{"color", {0, 0, 1}}}}}}}, cells.c_str());
    EXPECT_NE(us.self, nullptr) << us.error;
    const std::pair<nlohmann::json, std::string> refused[] = {
        {{{"Q", {{"colour", {0, 0, 0}}}}}, "types.Q"},
        {{{"F", {{"colour", {0, 2, 0}}}}}, "types.F.colour[1]"},
        {{{"F", {{"colour", 0.5}}}}, "types.F.colour"},
        {{{"F", {{"shine", 1}}}}, "types.F.shine"},
        {{{"F", {{"specular", 0.5}}}}, "types.F.specular"},
        {{{"F", 3}}, "types.F"},
    };
    for (const auto &[bad, field] : refused) {
        const Instance r({{"types", bad}}, cells.c_str());
        EXPECT_EQ(r.self, nullptr) << bad.dump();
        EXPECT_NE(r.error.find(field), std::string::npos) << r.error;
    }
    // One type's roughness from two places is ambiguous.
    const Instance twice(
        {{"roughness", "F=0.2"}, {"types", {{"F", {{"roughness", 0.3}}}}}},
        cells.c_str());
    EXPECT_EQ(twice.self, nullptr);
    EXPECT_NE(twice.error.find("types.F.roughness"), std::string::npos) << twice.error;
}

}  // namespace
}  // namespace pelage::test

namespace pelage::test {
namespace {

// Level of detail (mosaic_lod.h): footprints below a triangle's size see exactly the
// point-sampled pattern; from twice its size on, the filtered look of MosaicLod (built
// here directly from the same file); in between, one of the two, the filtered one with
// probability equal to the weight. The camera's AOVs keep naming the nearest cell at any
// footprint; lod = 0 never filters.
TEST(ClonalMosaicPlugin, WideFootprintsSeeTheFilteredLook) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, mesh_spec, 600);
    const Instance inst({}, cells.c_str()), off({{"lod", 0}}, cells.c_str());
    ASSERT_NE(inst.self, nullptr) << inst.error;
    const pattern::mosaic::MosaicPattern pattern(cells, mesh_spec);
    const pattern::mosaic::MosaicLod lod(
        pattern,
        [&](uint32_t c) {
            const sim::CellsFileType &t = pattern.types()[pattern.cells().type[c]];
            return pattern::mosaic::FilteredLook{
                {t.colour[0], t.colour[1], t.colour[2], t.eumelanin, t.pheomelanin}};
        },
        pattern.types().size());

    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0, 1);
    int differs = 0, filtered_in_ramp = 0, exact_in_ramp = 0;
    double ramp_weight = 0;
    for (int n = 0; n < 2000; ++n) {
        const uint32_t prim = rng() % 1280;
        float b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        const uint32_t depth = n % 2;
        // Footprints well below the size (weight 0) and beyond twice it (weight 1).
        const float small = 1e-4f, large = 1e3f;
        ASSERT_EQ(lod.weight(prim, small), 0.0f);
        ASSERT_EQ(lod.weight(prim, large), 1.0f);
        const PelageShade exact = off.shade(prim, b1, b2, small, depth);
        const PelageShade fine = inst.shade(prim, b1, b2, small, depth);
        ASSERT_EQ(std::memcmp(&exact, &fine, sizeof(PelageShade)), 0);

        const pattern::mosaic::FilteredLook f = lod.at(prim, b1, b2);
        const PelageShade wide = inst.shade(prim, b1, b2, large, depth);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(wide.albedo[k], f.v[k]);
        ASSERT_EQ(wide.eumelanin, f.v[3]);
        ASSERT_EQ(wide.pheomelanin, f.v[4]);
        differs += std::abs(wide.albedo[0] - exact.albedo[0]) > 0.05f;
        if (depth == 0) {  // the AOVs still name the nearest cell
            const PelageShade hard = off.shade(prim, b1, b2, 0, 0);
            ASSERT_EQ(wide.aov_written, 1u);
            ASSERT_EQ(wide.aov[0], hard.aov[0]);
            ASSERT_EQ(wide.aov[1], hard.aov[1]);
            ASSERT_EQ(wide.aov[2], hard.aov[2]);
        }
        // lod = 0 point-samples at any footprint (depth 1: the hard nearest-cell path).
        if (depth == 1) {
            const PelageShade never = off.shade(prim, b1, b2, large, 1);
            const PelageShade hard = off.shade(prim, b1, b2, 0, 1);
            ASSERT_EQ(std::memcmp(&never, &hard, sizeof(PelageShade)), 0);
        }
        // Half-way through the ramp (weight 0.3 here): either look, whole, and the
        // filtered one on about that fraction of the hits (stochastic filtering).
        float lo = small, hi = large;  // bisect for the footprint of weight 0.3
        for (int it = 0; it < 60; ++it) {
            const float mid = 0.5f * (lo + hi);
            (lod.weight(prim, mid) < 0.3f ? lo : hi) = mid;
        }
        ramp_weight += lod.weight(prim, hi);
        const PelageShade in_ramp = inst.shade(prim, b1, b2, hi, 1);
        const PelageShade exact_ramp = off.shade(prim, b1, b2, hi, 1);
        const bool took_filtered = in_ramp.albedo[0] == f.v[0] &&
                                   in_ramp.albedo[1] == f.v[1] &&
                                   in_ramp.albedo[2] == f.v[2];
        const bool took_exact =
            std::memcmp(&in_ramp, &exact_ramp, sizeof(PelageShade)) == 0;
        ASSERT_TRUE(took_filtered || took_exact) << n;
        filtered_in_ramp += took_filtered && !took_exact;
        exact_in_ramp += took_exact && !took_filtered;
        // The same hit always takes the same one (deterministic at any thread count).
        const PelageShade again = inst.shade(prim, b1, b2, hi, 1);
        ASSERT_EQ(std::memcmp(&in_ramp, &again, sizeof(PelageShade)), 0);
    }
    EXPECT_GT(differs, 100);  // the filtered look is not the point sample
    // Of the ramp hits where the two looks differ, about 30 % took the filtered one.
    const double fraction = double(filtered_in_ramp) / (filtered_in_ramp + exact_in_ramp);
    EXPECT_NEAR(ramp_weight / 2000, 0.3, 1e-3);
    EXPECT_NEAR(fraction, 0.3, 0.06) << filtered_in_ramp << " / " << exact_in_ramp;
}

// A triangle soup (pieces offset by 2e-3 of the diagonal, beyond the stitch, too small
// for a cell each):
// every hit is coloured by a cell, hard-edged or blended, and creating the instance
// warns with the share of the area that borrows its cells and what to do.
TEST(ClonalMosaicPlugin, EveryHitOnATriangleSoupHasACellAndTheSoupIsNamed) {
    TempDir tmp;
    const TriangleSoup soup =
        make_triangle_soup(sim::load_mesh(mesh_spec), 2e-3, 1.5e-3, 57);
    const std::string mesh = tmp.file("soup.off");
    write_off_exact(mesh, soup.mesh);
    const std::string cells = tmp.file("soup.cells");
    std::string err;
    ASSERT_EQ(run_pelage("sim --mesh " + mesh + " --preset " + two_type_preset(tmp, 300) +
                             " -o " + cells + " --surface input",
                         nullptr, &err),
              0)
        << err;
    const pattern::mosaic::MosaicPattern pattern(cells, mesh);
    const pattern::transfer::CellCoverReport &r = pattern.cover().report();
    ASSERT_GT(r.carried_pieces, 100u);

    testing::internal::CaptureStderr();
    const Instance hard({{"antialias", 0}}, cells.c_str(), mesh);
    const std::string warned = testing::internal::GetCapturedStderr();
    ASSERT_NE(hard.self, nullptr) << hard.error;
    const Instance soft({{"edge_width", 0.01}}, cells.c_str(), mesh);
    ASSERT_NE(soft.self, nullptr) << soft.error;
    char share[64];
    std::snprintf(share, sizeof share, "%.2f %% of the area of ",
                  100 * r.carried_area_share);
    EXPECT_NE(warned.find(std::string(share) + mesh), std::string::npos) << warned;
    EXPECT_NE(warned.find("triangle soup"), std::string::npos) << warned;
    EXPECT_NE(warned.find("Merge by Distance"), std::string::npos) << warned;

    size_t grey = 0;
    for (uint32_t prim = 0; prim < hard.mesh.num_triangles(); ++prim)
        for (const Instance *inst : {&hard, &soft}) {
            const PelageShade sh = inst->shade(prim, 0.3f, 0.3f);
            grey += sh.aov_written != 1 || sh.cell_type < 0;
        }
    EXPECT_EQ(grey, 0u) << "hits without a cell";
}

// A low-poly mesh is grown on a copy of itself split at its edge midpoints
// (sim/remesh/cell_scale_surface.h): the pattern is carried back exactly, and the
// note names pelage's own copy, not another triangulation of the user's (as it did on
// every low-poly animal).
TEST(ClonalMosaicPlugin, ALowPolyMeshGrownOnItsOwnSplitCopyIsNamedSo) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:0";  // 20 triangles
    const std::string cells = tmp.file("low.cells");
    std::string err;
    ASSERT_EQ(run_pelage("sim --mesh " + mesh + " --preset " +
                             two_type_preset(tmp, 3000) + " -o " + cells,
                         nullptr, &err),
              0)
        << err;
    const pattern::mosaic::MosaicPattern pattern(cells, mesh);
    ASSERT_NE(pattern.transfer(), nullptr) << "grown on the mesh itself: nothing to test";
    EXPECT_GT(pattern.num_triangles(), 20u);
    testing::internal::CaptureStderr();
    const Instance inst({}, cells.c_str(), mesh);
    const std::string warned = testing::internal::GetCapturedStderr();
    ASSERT_NE(inst.self, nullptr) << inst.error;
    EXPECT_NE(warned.find("was grown on pelage sim's copy of " + mesh +
                          " split at its edge midpoints"),
              std::string::npos)
        << warned;
    EXPECT_EQ(warned.find("triangulated otherwise"), std::string::npos) << warned;
    EXPECT_EQ(warned.find("another mesh"), std::string::npos) << warned;
    // The same split made by the user and grown on as it is: rendered on the coarse
    // mesh, that is another triangulation, and the plugin says so.
    const std::string split = tmp.file("split.off");
    write_off_exact(split,
                    sim::subdivide(sim::load_mesh(mesh), sim::Subdivision::midpoint));
    const std::string theirs = tmp.file("split.cells");
    ASSERT_EQ(
        run_pelage("sim --mesh " + split + " --preset " + two_type_preset(tmp, 300) +
                       " -o " + theirs + " --surface input",
                   nullptr, &err),
        0)
        << err;
    testing::internal::CaptureStderr();
    const Instance other({}, theirs.c_str(), mesh);
    const std::string told = testing::internal::GetCapturedStderr();
    ASSERT_NE(other.self, nullptr) << other.error;
    EXPECT_NE(told.find("triangulated otherwise"), std::string::npos) << told;
}

}  // namespace
}  // namespace pelage::test
