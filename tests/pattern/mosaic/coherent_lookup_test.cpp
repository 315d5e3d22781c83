// CoherentLookup: reusing the previous query's cell never changes a result, and on
// coherent queries (small steps, as camera hits along a row) it does reuse most of them.
#include "pattern/mosaic/coherent_lookup.h"

#include <gtest/gtest.h>

#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "tests/test_paths.h"

namespace pelage::pattern::mosaic {
namespace {

TEST(CoherentLookup, EqualsTheSearchBitForBitAndReusesMostCoherentQueries) {
    const sim::Surface s = sim::build_surface(test::sample_mesh("cow.off"));
    std::vector<CellOnSurface> list;
    uint32_t id = 0;
    for (const auto &p : sim::sample_surface_uniform(s.crps, 20000, 3)) {
        list.push_back({p.tri, p.p.x, p.p.y, id, uint8_t(id % 2)});
        ++id;
    }
    const CellTable cells = make_cell_table(s.crps.num_triangles(), list);
    const ClosestCellIndex index(s.crps, cells);
    CoherentLookup coherent;
    size_t calls = 0, blends = 0;
    // Walks of 200 steps across triangles (corner 0 towards the far edge), bands from 0
    // to about a tenth of a cell spacing: many cell boundaries are crossed, and steps
    // near them must not be reused wrongly.
    for (sim::TriId t = 0; t < s.crps.num_triangles(); t += 7) {
        for (int k = 0; k <= 200; ++k) {
            const float u = k / 200.0f;
            const float b1 = 0.6f * u, b2 = 0.3f * u + 0.2f * u * (1 - u);
            const float band = 1e-4f * float(k % 5);
            const auto a = coherent.find_three_within(index, 1, t, b1, b2, band);
            const auto b = index.find_three_within(t, b1, b2, band);
            ++calls;
            blends += b.index[1] != ClosestCell::none;
            for (int i = 0; i < 3; ++i) {
                ASSERT_EQ(a.index[i], b.index[i]) << t << " " << k << " " << i;
                ASSERT_EQ(a.d2[i], b.d2[i]) << t << " " << k << " " << i;
            }
        }
    }
    EXPECT_EQ(coherent.reused() + coherent.searched(), calls);
    EXPECT_GT(coherent.reused(), calls / 2) << coherent.searched() << " searched";
    // Blends (two or three cells within the band) are checked too, and since c2 is
    // kept, even most of them are reused: searches are fewer than blends.
    EXPECT_GT(blends, calls / 50);
    EXPECT_LT(coherent.searched(), blends) << blends << " blends of " << calls;
    // Another index (serial) or triangle is never served from the memory of this one.
    const size_t reused = coherent.reused();
    coherent.find_three_within(index, 2, 0, 0.1f, 0.1f, 0);
    coherent.find_three_within(index, 2, 1, 0.1f, 0.1f, 0);
    EXPECT_EQ(coherent.reused(), reused);
}

}  // namespace
}  // namespace pelage::pattern::mosaic
