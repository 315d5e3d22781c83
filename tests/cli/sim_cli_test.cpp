// `pelage sim`, `stats`, `preview` end to end: output contracts, determinism across
// thread counts, and bad input → exit 2 with nothing written.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

const std::string small_run =
    "sim --mesh procedural:sphere:20x20 --preset teo-table-7.2 --initial-cells 1500 "
    "--seed 4 ";

TEST(SimCli, StatsJsonHasTheContractKeys) {
    TempDir tmp;
    ASSERT_EQ(run_pelage(small_run + "-o " + tmp.file("a.cells") + " --stats-json " +
                         tmp.file("s.json")),
              0);
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    for (const char *k : {"triangles", "area", "cells_by_type", "spot_fraction",
                          "divisions", "relax_steps", "seconds"})
        EXPECT_TRUE(s.contains(k)) << k;
    EXPECT_EQ(s["triangles"], 760);
    EXPECT_EQ(s["relax_steps"], 50);
    const size_t f = s["cells_by_type"]["F"], b = s["cells_by_type"]["B"];
    EXPECT_EQ(f + b, 1500 + s["divisions"].get<size_t>());
    EXPECT_NEAR(s["spot_fraction"].get<double>(), double(f) / double(f + b), 1e-12);

    // Without --mesh the statistics are measured on the surface the file carries; with
    // the mesh it was grown on they are the same numbers (one definition of a spot,
    // through the renderer's closest-cell search).
    std::string out;
    ASSERT_EQ(
        run_pelage("stats " + tmp.file("a.cells") + " --area-samples 5000 --json", &out),
        0);
    const auto st = nlohmann::json::parse(out);
    for (const char *k : {"cells_by_type", "spot_fraction", "spot_count",
                          "spot_area_mean", "spot_area_quantiles", "largest_spot_cells"})
        EXPECT_TRUE(st.contains(k)) << k;
    EXPECT_FALSE(st.contains("spots"));  // the count-based definition is gone
    EXPECT_EQ(st["cells_by_type"], s["cells_by_type"]);
    EXPECT_GT(st["spot_count"].get<size_t>(), 0u);
    EXPECT_LE(st["spot_count"].get<size_t>(), f);
    EXPECT_LE(st["largest_spot_cells"].get<size_t>(), f);
    const auto &q = st["spot_area_quantiles"];
    EXPECT_LE(q["min"].get<double>(), q["median"].get<double>());
    EXPECT_LE(q["median"].get<double>(), q["max"].get<double>());
    EXPECT_GE(q["max"].get<double>(), st["spot_area_mean"].get<double>());
    ASSERT_EQ(run_pelage("stats " + tmp.file("a.cells") +
                             " --mesh procedural:sphere:20x20 --area-samples 5000 --json",
                         &out),
              0);
    const auto sa = nlohmann::json::parse(out);
    ASSERT_TRUE(sa.contains("area_fraction_by_type"));
    const double af = sa["area_fraction_by_type"]["F"],
                 ab = sa["area_fraction_by_type"]["B"];
    EXPECT_NEAR(af + ab, 1.0, 1e-12);
    EXPECT_NEAR(sa["spot_fraction_by_area"].get<double>(), af / (af + ab), 1e-12);
    EXPECT_EQ(sa["area_samples"], 5000);
    for (const char *k : {"spot_count", "spot_area_mean", "largest_spot_cells",
                          "area_fraction_by_type", "background_components"})
        EXPECT_EQ(sa[k], st[k]) << k;

    ASSERT_EQ(run_pelage("preview " + tmp.file("a.cells") + " --res 64 -o " +
                         tmp.file("p.png")),
              0);
    EXPECT_EQ(slurp(tmp.file("p.png")).substr(1, 3), "PNG");
    // The preview decodes (OpenImageIO writes it) and shows more than one colour.
    OIIO::ImageBuf png(tmp.file("p.png"));
    ASSERT_TRUE(png.read()) << png.geterror();
    EXPECT_EQ(png.spec().width, 64);
    EXPECT_EQ(png.spec().nchannels, 3);
    const auto range = OIIO::ImageBufAlgo::computePixelStats(png);
    EXPECT_GT(range.max[0] - range.min[0], 0.1f);
}

TEST(SimCli, SameSeedGivesIdenticalCellsAtOneAndTwoThreads) {
    TempDir tmp;
    ASSERT_EQ(run_pelage(small_run + "--threads 1 -o " + tmp.file("1.cells")), 0);
    ASSERT_EQ(run_pelage(small_run + "--threads 2 -o " + tmp.file("2.cells")), 0);
    ASSERT_EQ(
        run_pelage(small_run + "--threads 2 --relax global -o " + tmp.file("g2.cells")),
        0);
    ASSERT_EQ(
        run_pelage(small_run + "--threads 1 --relax global -o " + tmp.file("g1.cells")),
        0);
    EXPECT_EQ(slurp(tmp.file("1.cells")), slurp(tmp.file("2.cells")));
    EXPECT_EQ(slurp(tmp.file("g1.cells")), slurp(tmp.file("g2.cells")));
    EXPECT_NE(slurp(tmp.file("1.cells")), slurp(tmp.file("g1.cells")));
}

TEST(SimCli, BadPresetIsExit2AndWritesNothing) {
    TempDir tmp;
    const std::string outs =
        " -o " + tmp.file("x.cells") + " --stats-json " + tmp.file("x.json");
    std::string err;
    EXPECT_EQ(run_pelage("sim --mesh procedural:sphere:8x8 --preset no-such-thing" + outs,
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("no-such-thing"), std::string::npos) << err;
    const std::string bad = tmp.write(
        "bad.json",
        R"({"name": "b", "types": [{"name": "F", "colour": [1, 0], "division_time": 1, "initial_probability": 1}], "adhesion": [[0]], "simulation": {"initial_cells": 5, "w_r": 2, "w_d": 0.1, "rho": 1, "end_time": 1}})");
    EXPECT_EQ(run_pelage("sim --mesh procedural:sphere:8x8 --preset " + bad + outs,
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("types[0].colour: expected 3 numbers"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.cells")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.json")));
}

TEST(SimCli, CorruptedCellsFileIsExit2) {
    TempDir tmp;
    ASSERT_EQ(run_pelage(small_run + "-o " + tmp.file("a.cells")), 0);
    std::string bytes = slurp(tmp.file("a.cells"));
    tmp.write("trunc.cells", bytes.substr(0, bytes.size() / 2));
    bytes[bytes.size() / 2] ^= 1;
    tmp.write("flip.cells", bytes);
    std::string err;
    EXPECT_EQ(run_pelage("stats " + tmp.file("trunc.cells") + " --json", nullptr, &err),
              2);
    EXPECT_NE(err.find("trunc.cells"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("stats " + tmp.file("flip.cells") + " --json", nullptr, &err),
              2);
    EXPECT_NE(err.find("checksum"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("preview " + tmp.file("flip.cells") + " -o " + tmp.file("p.png"),
                         nullptr, &err),
              2);
    EXPECT_FALSE(std::filesystem::exists(tmp.file("p.png")));
}

}  // namespace
}  // namespace pelage::test
