// `pelage cells --export` and `pelage lookup`: looking up every exported cell position
// finds that very cell at distance ~0 — the export's barycentrics and the renderer's
// search agree. Bad point files are exit 2 with the line.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(CellsCli, ExportedCellsLookUpToThemselves) {
    TempDir tmp;
    const std::string mesh = "procedural:torus:24x12";
    const std::string cells = simulate_two_type_cells(tmp, mesh, 400, 0.4);
    ASSERT_EQ(run_pelage("cells " + cells + " --export " + tmp.file("cells.txt")), 0);

    std::ifstream in(tmp.file("cells.txt"));
    std::ofstream pts(tmp.file("pts.txt"));
    std::vector<std::pair<unsigned, unsigned>> expected;  // (id, type)
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        unsigned face, type, id;
        double b0, b1, b2;
        ASSERT_TRUE(ss >> face >> b0 >> b1 >> b2 >> type >> id) << line;
        EXPECT_NEAR(b0 + b1 + b2, 1.0, 1e-8);  // printed with 9 significant digits
        pts << face << " " << b0 << " " << b1 << " " << b2 << "\n";
        expected.push_back({id, type});
    }
    pts.close();
    ASSERT_EQ(expected.size(), 400u);
    std::string out, err;
    ASSERT_EQ(run_pelage("lookup " + cells + " --mesh " + mesh + " --points " +
                             tmp.file("pts.txt"),
                         &out, &err),
              0)
        << err;
    std::istringstream ss(out);
    for (const auto &[id, type] : expected) {
        unsigned got_id, got_type;
        double d;
        ASSERT_TRUE(ss >> got_id >> got_type >> d);
        EXPECT_EQ(got_id, id);
        EXPECT_EQ(got_type, type);
        EXPECT_LT(d, 1e-5);
    }
}

TEST(CellsCli, BadPointLinesAreExit2WithTheLine) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, "procedural:icosphere:1", 50);
    std::string err;
    const std::string pts =
        tmp.write("pts.txt", "0 0.2 0.3 0.5\n# comment\n99 0.2 0.3 0.5\n");
    EXPECT_EQ(
        run_pelage("lookup " + cells + " --mesh procedural:icosphere:1 --points " + pts,
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("pts.txt:3"), std::string::npos) << err;
    const std::string bad = tmp.write("bad.txt", "0 0.2 0.3\n");
    EXPECT_EQ(
        run_pelage("lookup " + cells + " --mesh procedural:icosphere:1 --points " + bad,
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("bad.txt:1"), std::string::npos) << err;
    // Another shape (a torus for cells grown on a sphere) is refused.
    EXPECT_EQ(
        run_pelage("lookup " + cells + " --mesh procedural:torus:24x12 --points " + pts,
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("another surface"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
