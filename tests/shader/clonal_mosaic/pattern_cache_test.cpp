// The plugin's pattern cache (shader/clonal_mosaic/pattern_cache.h): instances of one
// .cells file on one rest mesh share one pattern; another file, the same file rewritten,
// another mesh or another neighbourhood each get their own, built from the file as it is.
#include "shader/clonal_mosaic/pattern_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "sim/cells_io/cells_file.h"
#include "sim/mesh/mesh_load.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using pattern::mosaic::Neighbourhood;
using shader::clonal_mosaic::cached_pattern;

TEST(PatternCache, OneFileOnOneMeshIsBuiltOnce) {
    TempDir tmp;
    const std::string mesh_ref = "procedural:sphere:12x12";
    const std::string cells = simulate_two_type_cells(tmp, mesh_ref, 60);
    const sim::TriangleMesh mesh = sim::load_mesh(mesh_ref);
    const auto a = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::geodesic);
    const auto b = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::geodesic);
    EXPECT_EQ(a.get(), b.get()) << "a second instance rebuilt the pattern";
    // Kept alive between frames, when no instance holds it.
    const auto *first = a.get();
    { const auto drop_a = a; }
    const auto c = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::geodesic);
    EXPECT_EQ(c.get(), first);

    // Another neighbourhood is another index.
    const auto teo = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::unfolding_teo);
    EXPECT_NE(teo.get(), first);
}

TEST(PatternCache, ARewrittenFileOrAnotherMeshIsReadAgain) {
    TempDir tmp;
    const std::string mesh_ref = "procedural:sphere:12x12";
    const std::string cells = simulate_two_type_cells(tmp, mesh_ref, 60);
    const sim::TriangleMesh mesh = sim::load_mesh(mesh_ref);
    const auto before = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::geodesic);
    const size_t cells_before = before->cells().size();

    // The same name, other cells (grown again with another seed and count): the cache
    // must not hand out the old pattern.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // another mtime
    ASSERT_EQ(simulate_two_type_cells(tmp, mesh_ref, 90, 0.3, 7), cells);
    const auto after = cached_pattern(cells, mesh, mesh_ref, Neighbourhood::geodesic);
    EXPECT_NE(after.get(), before.get());
    EXPECT_EQ(after->cells().size(), sim::read_cells_file(cells).num_cells());
    EXPECT_NE(after->cells().size(), cells_before);

    // The same file on a moved copy of the mesh (another rest shape): its own pattern.
    sim::TriangleMesh moved = mesh;
    for (auto &p : moved.positions) p.x += 1e-3;
    const auto on_moved = cached_pattern(cells, moved, mesh_ref, Neighbourhood::geodesic);
    EXPECT_NE(on_moved.get(), after.get());
}

}  // namespace
}  // namespace pelage::test
