// The lane scans alone (lane_scan.h), on hand-built lists, against a brute-force sort of
// the same squared distances: the K nearest and their slots, the bound on the cells left,
// Teo's pruning (a block is skipped only when its bound lies beyond the K-th nearest),
// the empty list, the padded last block and exact ties — at four lanes and, where the CPU
// has AVX2, at eight.
#include "pattern/mosaic/lane_scan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace pelage::pattern::mosaic {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr uint32_t none = 0xffffffffu;

struct Cell {
    float x, y;
};

// Cells sorted by distance from `centre`, five to a block; each block's bound is a lower
// bound of its cells' distance from any query within `reach` of the centre (as the index
// bounds a region's list).
std::vector<CellBlock> make_list(std::vector<Cell> cells, Cell centre, float reach) {
    auto from_centre = [&](const Cell &c) {
        return std::hypot(c.x - centre.x, c.y - centre.y);
    };
    std::sort(cells.begin(), cells.end(), [&](const Cell &a, const Cell &b) {
        return from_centre(a) < from_centre(b);
    });
    std::vector<CellBlock> blocks;
    for (size_t i = 0; i < cells.size(); i += CellBlock::size) {
        CellBlock b{};
        const float lower = std::max(0.0f, from_centre(cells[i]) - reach) * 0.999f;
        b.bound2 = lower * lower;
        for (size_t l = 0; l < CellBlock::size; ++l) {
            const bool real = i + l < cells.size();
            b.x[l] = real ? cells[i + l].x : inf;
            b.y[l] = real ? cells[i + l].y : inf;
            b.cell[l] = real ? uint32_t(i + l) : none;
        }
        blocks.push_back(b);
    }
    return blocks;
}

float slot_d2(const std::vector<CellBlock> &list, uint32_t slot, Cell q) {
    const CellBlock &b = list[slot / CellBlock::size];
    return squared_distance(b.x[slot % CellBlock::size], b.y[slot % CellBlock::size],
                            {q.x, q.y});
}

std::vector<LaneScanners> widths() {
    std::vector<LaneScanners> w{lane_scanners(false)};
    if (lane_scanners(true).lanes == 8) w.push_back(lane_scanners(true));
    return w;
}

TEST(LaneScan, FindsTheBruteForceNearestAndPrunesOnlyBeyondThem) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    for (const LaneScanners &scan : widths()) {
        int pruned = 0;
        for (int trial = 0; trial < 400; ++trial) {
            std::vector<Cell> cells(1 + trial % 37);  // 1 … 37 cells: 1 … 8 blocks
            for (Cell &c : cells) c = {u(rng), u(rng)};
            const Cell centre{0.1f * u(rng), 0.1f * u(rng)};
            const float reach = 0.2f;
            const std::vector<CellBlock> list = make_list(cells, centre, reach);
            const Cell q{centre.x + 0.1f * u(rng), centre.y + 0.1f * u(rng)};
            std::vector<float> d2;
            for (const CellBlock &b : list)
                for (int l = 0; l < CellBlock::size; ++l)
                    if (b.cell[l] != none)
                        d2.push_back(squared_distance(b.x[l], b.y[l], {q.x, q.y}));
            std::sort(d2.begin(), d2.end());
            d2.push_back(inf);
            d2.push_back(inf);
            for (const int k : {1, 2}) {
                const LaneScan r = (k == 1 ? scan.nearest : scan.nearest_two)(
                    list.data(), list.data() + list.size(), {q.x, q.y});
                ASSERT_FALSE(r.tie);
                ASSERT_EQ(r.f1, d2[0]) << scan.lanes;
                ASSERT_EQ(slot_d2(list, r.slot1, q), d2[0]);
                if (k == 2) {
                    ASSERT_EQ(r.f2, d2[1]) << scan.lanes;
                    if (d2[1] != inf) {
                        ASSERT_EQ(slot_d2(list, r.slot2, q), d2[1]);
                    }
                }
                const CellBlock *end = list.data() + list.size();
                // Pruned only where the bound passes the K-th nearest; the cells left are
                // bounded by F_{K+1}, and equal to it when every block was scanned.
                ASSERT_TRUE(r.stop == end || r.stop->bound2 > d2[k - 1]);
                ASSERT_GE(r.rest, d2[k]);
                if (r.stop == end) {
                    ASSERT_EQ(r.rest, d2[k]);
                }
                pruned += r.stop != end;
            }
        }
        EXPECT_GT(pruned, 100) << "the lists must be long enough for the bound to prune";
    }
}

TEST(LaneScan, AnEmptyListFindsNothing) {
    for (const LaneScanners &scan : widths()) {
        const CellBlock none_at_all{};
        const LaneScan r = scan.nearest_two(&none_at_all, &none_at_all, {0, 0});
        EXPECT_EQ(r.stop, &none_at_all);
        EXPECT_EQ(r.f1, inf);
        EXPECT_EQ(r.f2, inf);
        EXPECT_EQ(r.rest, inf);
        EXPECT_FALSE(r.tie);
    }
}

// Two cells at one point tie exactly: the scan must say so (the caller then orders them
// by stable id), at K = 1 and K = 2, also when the tie is for second place.
TEST(LaneScan, ExactTiesAreReported) {
    for (const LaneScanners &scan : widths()) {
        const std::vector<CellBlock> first_tie =
            make_list({{0.5f, 0}, {0.5f, 0}, {0.9f, 0.3f}}, {0, 0}, 0.1f);
        const CellBlock *b = first_tie.data(), *e = b + first_tie.size();
        EXPECT_TRUE(scan.nearest(b, e, {0, 0}).tie);
        EXPECT_TRUE(scan.nearest_two(b, e, {0, 0}).tie);
        const std::vector<CellBlock> second_tie =
            make_list({{0.1f, 0}, {0.5f, 0}, {0, 0.5f}, {0.9f, 0}}, {0, 0}, 0.1f);
        b = second_tie.data();
        e = b + second_tie.size();
        EXPECT_FALSE(scan.nearest(b, e, {0, 0}).tie);
        EXPECT_TRUE(scan.nearest_two(b, e, {0, 0}).tie);
        EXPECT_FALSE(scan.nearest_two(b, e, {0.05f, 0.01f}).tie);
    }
}

}  // namespace
}  // namespace pelage::pattern::mosaic
