// `pelage bench lookup` end to end on a small sphere: the output contract's keys (other
// tools read them), the pruned search agreeing with the exhaustive one and the two lane
// widths with each other, reuse on the banded walks, and a bad mesh refused with exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(BenchLookupCli, PrintsTheContractKeysAndExactSearches) {
    std::string out, err;
    ASSERT_EQ(
        run_pelage(
            "bench lookup --mesh procedural:icosphere:2 --cell-count 800 --queries 4000 "
            "--threads 1",
            &out, &err),
        0)
        << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    ASSERT_TRUE(j.contains("runs"));
    ASSERT_EQ(j["runs"].size(), 1u);
    const nlohmann::json &r = j["runs"][0];
    for (const char *key :
         {"mesh", "cells", "ns_per_lookup", "exhaustive_agreement", "edge_disagreement",
          "ns_per_lookup_coherent", "ns_per_lookup_f1_only", "ns_per_lookup_banded_walk",
          "ns_per_lookup_banded_walk_reuse", "walk_reused", "ns_per_lookup_lod",
          "index_megabytes", "lanes", "ns_per_lookup_four_lanes", "lanes_agree",
          "checksum"})
        EXPECT_TRUE(r.contains(key)) << key;
    EXPECT_EQ(r["cells"].get<double>(), 800);
    EXPECT_GE(r["exhaustive_agreement"].get<double>(), 0.9999);
    EXPECT_GT(r["ns_per_lookup"].get<double>(), 0);
    EXPECT_GT(r["ns_per_lookup_lod"].get<double>(), 0);
    // Four or eight lanes, whichever the CPU runs, find the cells the four-lane scans do.
    EXPECT_TRUE(r["lanes"] == 4 || r["lanes"] == 8) << r["lanes"];
    EXPECT_TRUE(r["lanes_agree"].get<bool>());
    // Walks of 32 steps across triangles about two cells wide: most steps reuse.
    EXPECT_GT(r["walk_reused"].get<double>(), 0.3);
    EXPECT_LE(r["walk_reused"].get<double>(), 1.0);
}

TEST(BenchLookupCli, AMissingMeshIsExit2NamingIt) {
    std::string out, err;
    EXPECT_EQ(
        run_pelage("bench lookup --mesh /nonexistent/cow.off --queries 10", &out, &err),
        2);
    EXPECT_NE(err.find("/nonexistent/cow.off"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
