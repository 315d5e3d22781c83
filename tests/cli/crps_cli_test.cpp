// `pelage crps` end to end: the --stats-json output contract, and exit codes.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {

TEST(CrpsCli, StatsJsonHasTheContractKeysForTheSphere) {
    TempDir tmp;
    ASSERT_EQ(run_pelage("crps --mesh procedural:sphere:20x20 --stats-json " +
                         tmp.file("s.json")),
              0);
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    for (const char *k : {"triangles", "vertices", "edges", "boundary_edges",
                          "nonmanifold_edges", "degenerate_dropped", "area",
                          "roundtrip_max_error", "edge_map_max_error", "seconds"})
        EXPECT_TRUE(s.contains(k)) << k;
    EXPECT_EQ(s["triangles"], 760);
    EXPECT_EQ(s["vertices"], 382);
    EXPECT_EQ(s["edges"], 1140);  // closed: E = 3F/2
    EXPECT_EQ(s["boundary_edges"], 0);
    EXPECT_EQ(s["nonmanifold_edges"], 0);
    EXPECT_LT(s["roundtrip_max_error"].get<double>(), 1e-5);
    EXPECT_LT(s["edge_map_max_error"].get<double>(), 1e-5);
    // An inscribed polyhedron has less area than the unit sphere, but not much less.
    EXPECT_LT(s["area"].get<double>(), 4 * 3.14159265358979);
    EXPECT_GT(s["area"].get<double>(), 0.97 * 4 * 3.14159265358979);
}

TEST(CrpsCli, OpenMeshIsAcceptedAndItsBoundaryCounted) {
    TempDir tmp;
    ASSERT_EQ(
        run_pelage("crps --mesh procedural:plane:4x3 --stats-json " + tmp.file("s.json")),
        0);
    const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
    EXPECT_EQ(s["boundary_edges"], 2 * (4 + 3));
    EXPECT_EQ(s["triangles"], 24);
}

TEST(CrpsCli, MissingFileIsExit2AndNamesTheFile) {
    std::string err;
    EXPECT_EQ(run_pelage("crps --mesh /nonexistent/cow.off", nullptr, &err), 2);
    EXPECT_NE(err.find("/nonexistent/cow.off"), std::string::npos) << err;
}

}  // namespace pelage::test
