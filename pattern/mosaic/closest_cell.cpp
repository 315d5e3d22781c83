// Searches the closest-cell index (Teo 2006 §6.2, Fig. 6.2; see closest_cell.h). The
// index is built in closest_cell_build.cpp (see closest_cell_build.h).
#include "pattern/mosaic/closest_cell.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pattern/mosaic/lane_scan.h"
#include "pattern/mosaic/subdivision.h"

namespace pelage::pattern::mosaic {
namespace {

constexpr float inf_f = std::numeric_limits<float>::infinity();

}  // namespace

// Both inline into every search: a lookup is short enough that the cost of two calls
// would be a visible share of it.
[[gnu::always_inline]] inline const ClosestCellIndex::Block *ClosestCellIndex::blocks_at(
    sim::TriId t, float b1, float b2, const Block *&end) const {
    const uint32_t first = m_first_region[t], r = first & 3u;
    const uint32_t g = (first >> 2) + (r == 1 ? 0 : slot_at(r, b1, b2));
    end = m_blocks.data() + m_region_block[g + 1];
    return m_blocks.data() + m_region_block[g];
}

[[gnu::always_inline]] inline const ClosestCellIndex::Block *ClosestCellIndex::blocks_of(
    sim::TriId t, Vec2f q, const Block *&end) const {
    if ((m_first_region[t] & 3u) == 1) return blocks_at(t, 0, 0, end);
    // q's barycentric coordinates, by Cramer's rule on q - v0 = b1 e1 + b2 e2.
    const TriangleFrame &r = m_frames[t];
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
                if constexpr (dedupe) seen |= cell_of(n.index[j]) == cell_of(cell);
                if (d2[l] < n.d2[j] ||
                    (d2[l] == n.d2[j] && n.index[j] != ClosestCell::none &&
                     id[cell_of(cell)] < id[cell_of(n.index[j])]))
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
    static_assert(K == 1 || K == 2);
    const LaneScan r = (K == 1 ? m_lanes.nearest : m_lanes.nearest_two)(b, e, q);
    // An exact tie among the K + 1 nearest: the order by (distance, stable id) needs the
    // ids, which the reference scan reads. (Rare: equal floats of distinct points.)
    if (r.tie) {
        n = Nearest<K>();
        return scan<true, false, K>(b, e, q, n, -1, cells_left_d2);
    }
    // The k-th nearest is the cell in `slot`, at squared distance d2 (none when +inf).
    auto take = [&](int k, uint32_t slot, float d2, Vec2f &at) {
        if (d2 == inf_f) return;
        const Block &blk = b[slot / per_block];
        const uint32_t l = slot % per_block;
        n.d2[k] = d2;
        n.index[k] = blk.cell[l];
        at = {blk.x[l], blk.y[l]};
    };
    take(0, r.slot1, r.f1, n.nearest_at);
    if constexpr (K == 2) take(1, r.slot2, r.f2, n.second_at);
    if (cells_left_d2) *cells_left_d2 = r.rest;
    n.beyond_d2 = r.stop != e ? std::min(r.rest, r.stop->bound2) : r.rest;
    return r.stop;
}

float BentWindow::distance(Vec2f q) const {
    const float d = sigma + std::sqrt(squared_distance(sx, sy, q));
    return covers(q) ? d : std::numeric_limits<float>::infinity();
}

bool BentWindow::covers(Vec2f q) const {
    if (std::isnan(x0x)) return true;
    const float r0x = x0x - sx, r0y = x0y - sy, r1x = x1x - sx, r1y = x1y - sy;
    const float dx = q.x - sx, dy = q.y - sy;
    const float w = r0x * r1y - r0y * r1x;
    // A relative slack of 1e-5: points on the ray between two windows belong to both.
    const float tol = 1e-5f *
                      (std::abs(r0x) + std::abs(r0y) + std::abs(r1x) + std::abs(r1y)) *
                      (std::abs(dx) + std::abs(dy));
    const float a = r0x * dy - r0y * dx, b = dx * r1y - dy * r1x;
    return w >= 0 ? (a >= -tol && b >= -tol) : (a <= tol && b <= tol);
}

float ClosestCellIndex::bent_distance(uint32_t entry, Vec2f q, float listed) const {
    float best = std::numeric_limits<float>::infinity(), any = best;
    const size_t n = m_bent_windows.size();
    for (size_t i = entry & ~bent_flag;;) {
        const BentWindow &w = m_bent_windows[i];
        const float d = w.sigma + std::sqrt(squared_distance(w.sx, w.sy, q));
        any = std::min(any, d);
        if (d < best && w.covers(q)) best = d;
        if (++i == n || m_bent_windows[i].tag != BentWindow::more) break;
    }
    // A rounding error outside every wedge: the nearest formula, else (no window at all,
    // which the build never lists) the listed position.
    return std::isinf(best) ? (std::isinf(any) ? listed : any) : best;
}

template <int K>
void ClosestCellIndex::resolve(Nearest<K> &n, Vec2f q) const {
    bool any = false;
    for (int k = 0; k < K; ++k) {
        const uint32_t e = n.index[k];
        if (e == ClosestCell::none || !(e & bent_flag)) continue;
        const float d = bent_distance(e, q, std::sqrt(n.d2[k]));
        n.index[k] = cell_of(e);
        n.d2[k] = d * d;
        any = true;
    }
    if (n.second != ClosestCell::none && (n.second & bent_flag)) {
        n.second = cell_of(n.second);
        any = true;
    }
    if (any) n.bent = true;
}

template void ClosestCellIndex::resolve<1>(Nearest<1> &, Vec2f) const;
template void ClosestCellIndex::resolve<2>(Nearest<2> &, Vec2f) const;
template void ClosestCellIndex::resolve<3>(Nearest<3> &, Vec2f) const;

ClosestCell ClosestCellIndex::find(sim::TriId t, Vec2f q) const {
    Nearest<2> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan_lanes<2>(b, e, q, n);
    resolve(n, q);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, Vec2f q) const {
    Nearest<1> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan_lanes<1>(b, e, q, n);
    resolve(n, q);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three(sim::TriId t, Vec2f q) const {
    Nearest<3> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan<true, false, 3>(b, e, q, n);
    resolve(n, q);
    return n;
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, Vec2f q,
                                                                 float band) const {
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    Nearest<3> n = three_within(b, e, q, band);
    resolve(n, q);
    return n;
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::three_within(const Block *b,
                                                            const Block *e, Vec2f q,
                                                            float band) const {
    // Two passes over the same (by then cached) blocks: the two nearest cells, then,
    // only when the second lies within F1 + band, whatever else does — so most hits cost
    // one two-nearest search. The result is what one three-nearest scan
    // cut at F1 + band gives (the second pass keeps the same (distance, id) order).
    // The first pass also leaves what CoherentLookup needs to reuse the result for
    // the next hits: the second cell's position and a lower bound on F3. It runs lane
    // by lane with eight lanes, with the insertion scan otherwise (closest_cell.h: with
    // four lanes it is the better fit for camera hits); the same bits either way.
    Nearest<2> first;
    float cells_left_d2;
    const Block *stop = m_lanes.lanes == 8
                            ? scan_lanes<2>(b, e, q, first, &cells_left_d2)
                            : scan<true, false, 2>(b, e, q, first, -1, &cells_left_d2);
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
                     id[cell_of(cell)] < id[cell_of(n.index[j])]))
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
    const Vec2f q = point(t, b1, b2);
    scan_lanes<1>(b, e, q, n);
    resolve(n, q);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within_listed(
    sim::TriId t, float b1, float b2, float band) const {
    const Block *e;
    const Block *b = blocks_at(t, b1, b2, e);
    return three_within(b, e, point(t, b1, b2), band);
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, float b1,
                                                                 float b2,
                                                                 float band) const {
    const Block *e;
    const Block *b = blocks_at(t, b1, b2, e);
    const Vec2f q = point(t, b1, b2);
    Nearest<3> n = three_within(b, e, q, band);
    resolve(n, q);
    return n;
}

ClosestCell ClosestCellIndex::find_exhaustive(sim::TriId t, Vec2f q) const {
    // The whole of q's region list, without pruning.
    Nearest<2> n;
    const Block *e;
    const Block *b = blocks_of(t, q, e);
    scan<false, false, 2>(b, e, q, n);
    resolve(n, q);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

float ClosestCellIndex::distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const {
    const Block *e;
    for (const Block *b = blocks_of(t, q, e); b != e; ++b)
        for (int l = 0; l < per_block; ++l)
            if (cell_of(b->cell[l]) == cell) {
                if (!(b->cell[l] & bent_flag))
                    return std::hypot(b->x[l] - q.x, b->y[l] - q.y);
                return bent_distance(b->cell[l], q,
                                     std::hypot(b->x[l] - q.x, b->y[l] - q.y));
            }
    return std::numeric_limits<float>::infinity();
}

}  // namespace pelage::pattern::mosaic
