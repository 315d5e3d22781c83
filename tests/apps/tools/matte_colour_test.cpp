// apps/tools/matte_colour.h against an analytic answer: a convex Lambertian object in
// a white furnace (uniform environment of radiance 1) shows its albedo at every point,
// so the mean colour under each cell type's matte is that type's colour.
#include "apps/tools/matte_colour.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace pelage::test
