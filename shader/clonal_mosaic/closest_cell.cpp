// Searches the closest-cell index (Teo 2006 §6.2, Fig. 6.2; see closest_cell.h). The
// index is built in closest_cell_build.cpp.
#include "shader/clonal_mosaic/closest_cell.h"

#include "shader/clonal_mosaic/lane_nearest.h"
#include "shader/clonal_mosaic/subdivision.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace pelage::shader {
namespace {

constexpr float inf_f = std::numeric_limits<float>::infinity();

}  // namespace

const ClosestCellIndex::Block *ClosestCellIndex::blocks_at(sim::TriId t, float b1,
                                                           float b2,
                                                           const Block *&end) const {
    const uint32_t first = m_first_region[t], r = first & 3u;
    const uint32_t g = (first >> 2) + (r == 1 ? 0 : slot_at(r, b1, b2));
    end = m_blocks.data() + m_region_block[g + 1];
    return m_blocks.data() + m_region_block[g];
}

const ClosestCellIndex::Block *ClosestCellIndex::blocks_of(sim::TriId t, Vec2f q,
                                                           const Block *&end) const {
    if ((m_first_region[t] & 3u) == 1) return blocks_at(t, 0, 0, end);
    // q's barycentric coordinates, by Cramer's rule on q - v0 = b1 e1 + b2 e2.
    const Frame &r = m_frames[t];
    const float dx = q.x - r.v0x, dy = q.y - r.v0y;
    return blocks_at(t, (dx * r.e2y - dy * r.e2x) * r.inv_det,
                     (r.e1x * dy - r.e1y * dx) * r.inv_det, end);
}

template <bool prune, bool dedupe, int K>
const ClosestCellIndex::Block *ClosestCellIndex::scan(const Block *b, const Block *e,
                                                      Vec2f q, Nearest<K> &n, float band,
                                                      float *cells_left_d2) const {
    const uint32_t *id = m_cells->id.data();
    // D_min² of Teo Fig. 6.2: beyond it no cell matters any more — the squared distance
    // to the K-th nearest found so far, or to F1 + band when that is nearer (band >= 0).
    auto radius2 = [&] {
        if (band < 0) return n.d2[K - 1];
        const float cap = std::sqrt(n.d2[0]) + band;
        return std::min(n.d2[K - 1], cap * cap);
    };
    float d_min2 = radius2();
    // A lower bound on the squared distance of every cell not kept: those scanned and
    // passed over or pushed out, and the bound of the first block not scanned.
    float rest = std::numeric_limits<float>::infinity();
    for (; b != e; ++b) {
        // Blocks are sorted by their cells' distance from the region: once a block
        // lies beyond D_min, so do all after it.
        if constexpr (prune)
            if (b->bound2 > d_min2) break;
        float d2[per_block];
        for (int l = 0; l < per_block; ++l) d2[l] = squared_distance(b->x[l], b->y[l], q);
        if (const float m = *std::min_element(d2, d2 + per_block); m > d_min2) {
            rest = std::min(rest, m);
            continue;  // the common case
        }
        for (int l = 0; l < per_block; ++l) {
            const uint32_t cell = b->cell[l];
            if (d2[l] > d_min2 || cell == ClosestCell::none) {
                rest = std::min(rest, d2[l]);
                continue;
            }
            // Order by (distance, stable id); a cell listed in several regions (the
            // exhaustive scan) enters once.
            int pos = K;
            bool seen = false;
            for (int j = K - 1; j >= 0; --j) {
                if constexpr (dedupe) seen |= n.index[j] == cell;
                if (d2[l] < n.d2[j] ||
                    (d2[l] == n.d2[j] && n.index[j] != ClosestCell::none &&
                     id[cell] < id[n.index[j]]))
                    pos = j;
            }
            if (seen) continue;
            if (pos == K) {
                rest = std::min(rest, d2[l]);
                continue;
            }
            rest = std::min(rest, n.d2[K - 1]);  // pushed out (or +inf: an empty slot)
            for (int j = K - 1; j > pos; --j) {
                n.d2[j] = n.d2[j - 1];
                n.index[j] = n.index[j - 1];
            }
            n.d2[pos] = d2[l];
            n.index[pos] = cell;
            if (pos == 0) {
                n.second_at = n.nearest_at;
                n.nearest_at = {b->x[l], b->y[l]};
            } else if (pos == 1) {
                n.second_at = {b->x[l], b->y[l]};
            }
            d_min2 = radius2();
        }
    }
    if (cells_left_d2) *cells_left_d2 = rest;
    n.beyond_d2 = b != e ? std::min(rest, b->bound2) : rest;
    return b;
}

template <int K>
const ClosestCellIndex::Block *ClosestCellIndex::scan_lanes(const Block *b,
                                                            const Block *e, Vec2f q,
                                                            Nearest<K> &n,
                                                            float *cells_left_d2) const {
    static_assert((K == 1 || K == 2) && per_block == 5);
    using namespace lanes;
    // Lane l keeps the K nearest of the cells it has seen (the l-th of each block) and
    // the least distance of the others; the K nearest overall are among the lanes'. So
    // nothing branches on what a distance comparison decides (the order of distances in
    // a list is unpredictable): lanes 0-3 in one vector (lo), lane 4 in another (hi,
    // lanes 5-7 +inf). A cell is named by its slot in the list (5 per block): its index
    // and position are read once, at the end.
    LaneNearest<K> lo, hi;
    const Lanes4f qx = splat(q.x), qy = splat(q.y), inf4 = splat(inf_f);
    const Block *const first = b;
    Lanes4u slot = {0, 1, 2, 3};
    float d_min2 = inf_f;
    for (; b != e; ++b, slot += per_block) {
        if (b->bound2 > d_min2) break;  // sorted by bound: all later blocks lie beyond
        Lanes4f x, y;
        std::memcpy(&x, b->x, sizeof x);
        std::memcpy(&y, b->y, sizeof y);
        // squared_distance(), four at a time: the same operations, the same bits.
        const Lanes4f dx = x - qx, dy = y - qy;
        lo.add(dx * dx + dy * dy, slot);
        Lanes4f d4 = inf4;
        d4[0] = squared_distance(b->x[4], b->y[4], q);
        hi.add(d4, slot + 4);
        // D_min² (Teo Fig. 6.2): the K-th nearest so far. For K = 2 the least of the
        // lanes' nearest but f1's lane, and that lane's second (when two lanes tie at f1
        // this is more than F2: only ever looser, which scans more, not less).
        const float f1 = hmin(vmin(lo.m0, hi.m0));
        if constexpr (K == 1) {
            d_min2 = f1;
        } else {
            const Lanes4f at = splat(f1);
            d_min2 = hmin(vmin(lo.m0 == at ? lo.m1 : lo.m0, hi.m0 == at ? hi.m1 : hi.m0));
        }
    }
    // The nearest: the lane at f1 (exactly one, else a tie); then, for K = 2, the least
    // of the others' nearest and that lane's second. What is left bounds the rest.
    const float f1 = hmin(vmin(lo.m0, hi.m0));
    const Lanes4f at1 = splat(f1);
    const Lanes4i a_lo = lo.m0 == at1, a_hi = hi.m0 == at1;
    bool tie = f1 != inf_f && hcount(a_lo) + hcount(a_hi) > 1;
    const uint32_t slot1 = hor((Lanes4u(a_lo) & lo.s0) | (Lanes4u(a_hi) & hi.s0));
    float f2 = inf_f, rest;
    uint32_t slot2 = 0;
    if constexpr (K == 1) {
        rest = hmin(
            vmin(vmin(lo.rest, hi.rest), vmin(a_lo ? inf4 : lo.m0, a_hi ? inf4 : hi.m0)));
        tie |= f1 != inf_f && f1 == rest;
    } else {
        const Lanes4f c_lo = a_lo ? lo.m1 : lo.m0, c_hi = a_hi ? hi.m1 : hi.m0;
        f2 = hmin(vmin(c_lo, c_hi));
        const Lanes4f at2 = splat(f2);
        const Lanes4i b_lo = c_lo == at2, b_hi = c_hi == at2;
        tie |= f2 != inf_f && (f2 == f1 || hcount(b_lo) + hcount(b_hi) > 1);
        slot2 = hor((Lanes4u(b_lo) & (a_lo ? lo.s1 : lo.s0)) |
                    (Lanes4u(b_hi) & (a_hi ? hi.s1 : hi.s0)));
        // Left in the lanes: the second of f2's lane unless it was f1's too, and the
        // others' candidates.
        const Lanes4f r_lo = b_lo ? (a_lo ? inf4 : lo.m1) : c_lo;
        const Lanes4f r_hi = b_hi ? (a_hi ? inf4 : hi.m1) : c_hi;
        rest = hmin(vmin(vmin(lo.rest, hi.rest), vmin(r_lo, r_hi)));
        tie |= f2 != inf_f && f2 == rest;
    }
    // An exact tie among the K + 1 nearest: the order by (distance, stable id) needs the
    // ids, which the reference scan reads. (Rare: equal floats of distinct points.)
    if (tie) {
        n = Nearest<K>();
        return scan<true, false, K>(first, e, q, n, -1, cells_left_d2);
    }
    // The k-th nearest is the cell in `slot`, at squared distance d2 (none when +inf).
    auto take = [&](int k, uint32_t slot, float d2, Vec2f &at) {
        if (d2 == inf_f) return;
        const Block &blk = first[slot / per_block];
        const uint32_t l = slot % per_block;
        n.d2[k] = d2;
        n.index[k] = blk.cell[l];
        at = {blk.x[l], blk.y[l]};
    };
    take(0, slot1, f1, n.nearest_at);
    if constexpr (K == 2) take(1, slot2, f2, n.second_at);
    if (cells_left_d2) *cells_left_d2 = rest;
    n.beyond_d2 = b != e ? std::min(rest, b->bound2) : rest;
    return b;
}

ClosestCell ClosestCellIndex::find(sim::TriId t, Vec2f q) const {
    Nearest<2> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan_lanes<2>(b, e, q, n);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, Vec2f q) const {
    Nearest<1> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan_lanes<1>(b, e, q, n);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three(sim::TriId t, Vec2f q) const {
    Nearest<3> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan<true, false, 3>(b, e, q, n);
    return n;
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, Vec2f q,
                                                                 float band) const {
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    return three_within(b, e, q, band);
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::three_within(const Block *b,
                                                            const Block *e, Vec2f q,
                                                            float band) const {
    // Two passes over the same (by then cached) blocks: the two nearest cells, then,
    // only when the second lies within F1 + band, whatever else does — so most hits cost
    // one two-nearest search. The result is what one three-nearest scan
    // cut at F1 + band gives (the second pass keeps the same (distance, id) order).
    // The first pass also leaves what CoherentLookup needs to reuse the result for
    // the next hits: the second cell's position and a lower bound on F3.
    Nearest<2> first;
    float cells_left_d2;
    const Block *stop = scan<true, false, 2>(b, e, q, first, -1, &cells_left_d2);
    Nearest<3> n;
    n.d2[0] = first.d2[0];
    n.index[0] = first.index[0];
    n.nearest_at = first.nearest_at;
    n.second_at = first.second_at;
    n.second = first.index[1];
    n.third_d2 = first.beyond_d2;
    if (stop != e) {
        // The pruned block's bound is measured from the whole region, so it is loose
        // about q: its own cells and the next block's bound make a tighter F3 bound,
        // and a reused result reaches farther (one more, mostly prefetched, line).
        float m = stop + 1 != e ? stop[1].bound2 : inf_f;
        for (int l = 0; l < per_block; ++l)
            m = std::min(m, squared_distance(stop->x[l], stop->y[l], q));
        n.third_d2 = std::min(cells_left_d2, m);
    }
    if (first.index[0] == ClosestCell::none) return n;
    const float cap = std::sqrt(first.d2[0]) + std::max(band, 0.0f);
    const float cap2 = cap * cap;
    // The second-nearest cell lies beyond F1 + band (most hits): so does every other,
    // and the second pass would find nothing. (It computes the same d2 bits.)
    if (!(first.d2[1] <= cap2)) {
        n.next_d2 = first.d2[1];
        return n;
    }
    // The second lies within it but every other cell beyond (n.third_d2 bounds them
    // all): the second pass would find the second cell alone.
    if (n.third_d2 > cap2) {
        n.d2[1] = first.d2[1];
        n.index[1] = first.index[1];
        return n;
    }
    const uint32_t *id = m_cells->id.data();
    for (; b != e && b->bound2 <= cap2; ++b) {
        float d2[per_block];
        for (int l = 0; l < per_block; ++l) d2[l] = squared_distance(b->x[l], b->y[l], q);
        if (*std::min_element(d2, d2 + per_block) > cap2) continue;
        for (int l = 0; l < per_block; ++l) {
            const uint32_t cell = b->cell[l];
            if (!(d2[l] <= cap2) || cell == ClosestCell::none) continue;
            if (cell == n.index[0] && d2[l] == n.d2[0]) continue;  // the nearest itself
            // Insert into slots 1, 2 by (distance, stable id), as scan() orders.
            int pos = 3;
            for (int j = 2; j >= 1; --j)
                if (d2[l] < n.d2[j] ||
                    (d2[l] == n.d2[j] && n.index[j] != ClosestCell::none &&
                     id[cell] < id[n.index[j]]))
                    pos = j;
            if (pos == 3) continue;
            if (pos == 1) {
                n.d2[2] = n.d2[1];
                n.index[2] = n.index[1];
            }
            n.d2[pos] = d2[l];
            n.index[pos] = cell;
        }
    }
    if (n.index[1] == ClosestCell::none) n.next_d2 = first.d2[1];
    return n;
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, float b1, float b2) const {
    Nearest<1> n;
    const Block *e;
    const Block *b = blocks_at(t, b1, b2, e);
    scan_lanes<1>(b, e, point(t, b1, b2), n);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, float b1,
                                                                 float b2,
                                                                 float band) const {
    const Block *e;
    const Block *b = blocks_at(t, b1, b2, e);
    return three_within(b, e, point(t, b1, b2), band);
}

ClosestCell ClosestCellIndex::find_exhaustive(sim::TriId t, Vec2f q) const {
    // Every region's list.
    Nearest<2> n;
    scan<false, true, 2>(m_blocks.data() + m_region_block[m_first_region[t] >> 2],
                         m_blocks.data() + m_region_block[m_first_region[t + 1] >> 2], q,
                         n);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

float ClosestCellIndex::distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const {
    const Block *e;
    for (const Block *b = blocks_of(t, q, e); b != e; ++b)
        for (int l = 0; l < per_block; ++l)
            if (b->cell[l] == cell) return std::hypot(b->x[l] - q.x, b->y[l] - q.y);
    return std::numeric_limits<float>::infinity();
}

}  // namespace pelage::shader
