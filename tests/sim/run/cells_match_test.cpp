// A scene's "pattern" is grown again when what it was grown on changed (sim/run's
// cells_match): for one object of a file (FILE#NAME) the file's content counts as for a
// whole file, so an edited file is never rendered with the cells of its old shape.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/cells_io/cells_file.h"
#include "sim/mesh/mesh_objects.h"
#include "sim/run/grow_cells.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// Two octahedra, objects "a" and "b"; `shift` moves a's first vertex.
std::string two_objects(double shift) {
    std::string obj;
    for (int o = 0; o < 2; ++o) {
        obj += std::string("o ") + (o ? "b" : "a") + "\n";
        const double x = 3.0 * o;
        obj += "v " + std::to_string(x + 1 + (o ? 0.0 : shift)) + " 0 0\nv " +
               std::to_string(x - 1) + " 0 0\n";
        obj += "v " + std::to_string(x) + " 1 0\nv " + std::to_string(x) + " -1 0\n";
        obj += "v " + std::to_string(x) + " 0 1\nv " + std::to_string(x) + " 0 -1\n";
        const int b = 6 * o;
        const int faces[8][3] = {{1, 3, 5}, {3, 2, 5}, {2, 4, 5}, {4, 1, 5},
                                 {3, 1, 6}, {2, 3, 6}, {4, 2, 6}, {1, 4, 6}};
        for (const auto &f : faces)
            obj += "f " + std::to_string(b + f[0]) + " " + std::to_string(b + f[1]) +
                   " " + std::to_string(b + f[2]) + "\n";
    }
    return obj;
}

TEST(CellsMatch, OneObjectOfAnEditedFileIsGrownAgain) {
    TempDir tmp;
    const std::string file = tmp.write("pair.obj", two_objects(0));
    sim::GrowRequest r;
    r.mesh = file + "#a";
    r.preset = two_type_preset(tmp, 12);
    r.seed = 3;
    r.simplify = false;
    const std::string cells = tmp.file("a.cells");
    sim::write_cells_file(cells, sim::grow_cells(r).data);
    std::string why;
    EXPECT_TRUE(sim::cells_match(cells, r, &why)) << why;

    // Another object of the same file is another mesh.
    sim::GrowRequest other = r;
    other.mesh = file + "#b";
    EXPECT_FALSE(sim::cells_match(cells, other, &why));
    EXPECT_EQ(why, "grown on another mesh");

    // The file edited under the same name: the old cells are stale.
    tmp.write("pair.obj", two_objects(0.25));
    EXPECT_FALSE(sim::cells_match(cells, r, &why));
    EXPECT_EQ(why, "grown on another mesh");
}

// A file an older pelage wrote, without the anisotropy field the fur reads: grown again.
TEST(CellsMatch, AFileWithoutTheRecordedFieldIsGrownAgain) {
    TempDir tmp;
    sim::GrowRequest r;
    r.mesh = tmp.write("pair.obj", two_objects(0)) + "#a";
    r.preset = two_type_preset(tmp, 12);
    r.simplify = false;
    const std::string cells = tmp.file("a.cells");
    sim::CellsData data = sim::grow_cells(r).data;
    nlohmann::json params = nlohmann::json::parse(data.params_json);
    ASSERT_TRUE(params.contains("anisotropy_field"));
    EXPECT_TRUE(params["anisotropy_field"].is_null());  // the preset has none
    params.erase("anisotropy_field");
    data.params_json = params.dump();
    sim::write_cells_file(cells, data);
    std::string why;
    EXPECT_FALSE(sim::cells_match(cells, r, &why));
    EXPECT_NE(why.find("older pelage"), std::string::npos) << why;
}

TEST(CellsMatch, AMeshReferenceIsHashedByContent) {
    TempDir tmp;
    const std::string a = tmp.write("x.obj", two_objects(0));
    const std::string b = tmp.write("y.obj", two_objects(0));  // the same bytes
    EXPECT_EQ(sim::mesh_reference_hash(a), sim::mesh_reference_hash(b));
    EXPECT_EQ(sim::mesh_reference_hash(a + "#a"), sim::mesh_reference_hash(b + "#a"));
    EXPECT_NE(sim::mesh_reference_hash(a + "#a"), sim::mesh_reference_hash(a + "#b"));
    EXPECT_NE(sim::mesh_reference_hash(a + "#a"), sim::mesh_reference_hash(a));
    EXPECT_NE(sim::mesh_reference_hash(a + "#a"), "");
    EXPECT_EQ(sim::mesh_reference_hash(tmp.file("missing.obj")), "");
}

}  // namespace
}  // namespace pelage::test
