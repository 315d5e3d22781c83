// apps/tools/matte_colour.h against an analytic answer: a convex Lambertian object in
// a white furnace (uniform environment of radiance 1) shows its albedo at every point,
// so the mean colour under each cell type's matte is that type's colour.
#include "apps/tools/matte_colour.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "renderer/image/cryptomatte_read.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(MatteColour, EachTypeShowsItsAlbedoInAWhiteFurnace) {
    TempDir tmp;
    const std::string mesh = "procedural:icosphere:3";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 300);
    const std::string scene = tmp.write("s.json", R"({
      "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 64, "height": 64, "spp": 64, "cryptomatte": true},
      "lights": [{"type": "environment", "color": 1}],
      "objects": [{"name": "ball", "mesh": ")" + mesh +
                                                      R"(", "cells": ")" + cells +
                                                      R"(",
                   "material": {"shader": "clonal_mosaic", "params": {"jitter": 0}}}]
    })");
    const std::string exr = tmp.file("o.exr");
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + exr), 0);
    const sim::CellsData data = sim::read_cells_file(cells);
    const auto colours = renderer::mean_colour_by_matte(exr, "type");
    ASSERT_EQ(colours.size(), data.types.size());
    for (const renderer::MatteColour &c : colours) {
        const sim::CellsFileType *type = nullptr;
        for (const sim::CellsFileType &t : data.types)
            if (t.name == c.name) type = &t;
        ASSERT_NE(type, nullptr) << c.name;
        EXPECT_GT(c.pixels, 100u) << c.name;
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(c.mean[k], type->colour[k], 0.02 * type->colour[k] + 1e-3)
                << c.name << " channel " << k;
    }
    // The object layer: one name, both types together.
    const auto object = renderer::mean_colour_by_matte(exr, "CryptoObject");
    ASSERT_EQ(object.size(), 1u);
    EXPECT_EQ(object[0].name, "ball");
    EXPECT_GT(object[0].pixels, colours[0].pixels + colours[1].pixels - 10);
    EXPECT_THROW(renderer::mean_colour_by_matte(exr, "clone_of_nothing"), InputError);
    EXPECT_THROW(renderer::mean_colour_by_matte(tmp.file("none.exr"), "type"),
                 InputError);
}

// The interior of a matte, counted by hand: a 4x3 block of full coverage in a 7x5
// frame, one pixel of it at 0.98, and a covered column along the frame's right edge.
TEST(MatteColour, TheInteriorKeepsPixelsWhoseNeighboursAreCoveredToo) {
    renderer::Matte m;
    m.width = 7;
    m.height = 5;
    m.alpha.assign(35, 0.f);
    auto at = [&](int x, int y) { return size_t(y * 7 + x); };
    for (int y = 1; y <= 3; ++y)
        for (int x = 1; x <= 4; ++x) m.alpha[at(x, y)] = 1.f;
    m.alpha[at(1, 1)] = 0.98f;                            // below min_coverage
    for (int y = 0; y < 5; ++y) m.alpha[at(6, y)] = 1.f;  // the right edge
    auto count = [](const std::vector<uint8_t> &v) {
        return std::count(v.begin(), v.end(), 1);
    };
    const auto e0 = renderer::matte_interior(m, 0.99f, 0);
    EXPECT_EQ(count(e0), 11 + 5);
    EXPECT_EQ(e0[at(1, 1)], 0);
    // Erode 1: of the block's inner pixels (2, 2) and (3, 2), only (3, 2) has its eight
    // neighbours covered ((2, 2) touches (1, 1)); the edge column has pixels beyond the
    // frame, which count as uncovered.
    const auto e1 = renderer::matte_interior(m, 0.99f, 1);
    EXPECT_EQ(count(e1), 1);
    EXPECT_EQ(e1[at(3, 2)], 1);
    // Erode 2 leaves nothing; a lower threshold takes (1, 1) back.
    EXPECT_EQ(count(renderer::matte_interior(m, 0.99f, 2)), 0);
    EXPECT_EQ(count(renderer::matte_interior(m, 0.95f, 0)), 12 + 5);
}

}  // namespace
}  // namespace pelage::test
