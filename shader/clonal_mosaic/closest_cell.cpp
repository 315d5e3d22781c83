// Implements Teo 2006 §6.2 (see closest_cell.h).
#include "shader/clonal_mosaic/closest_cell.h"

#include "shader/clonal_mosaic/lane_nearest.h"
#include "shader/clonal_mosaic/subdivision.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace pelage::shader {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr float inf_f = std::numeric_limits<float>::infinity();

}  // namespace

// One triangle's lists for one choice of regions.
struct ClosestCellIndex::Built {
    Frame frame{};
    uint32_t regions = 1;  // sub-triangles per side searched at run time
    std::array<uint32_t, max_subdivision * max_subdivision> end{};  // each list's, in blocks
    std::vector<Block> blocks;
    size_t entries = 0, distinct_triangles = 0, longest = 0;
};

ClosestCellIndex::ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                                   const ClosestCellOptions &options)
    : m_cells(&cells), m_options(options) {
    const auto t0 = std::chrono::steady_clock::now();
    const size_t nt = crps.num_triangles();
    double area = 0;
    for (sim::TriId t = 0; t < nt; ++t) area += crps.frame(t).area;
    m_spacing = std::sqrt(area / std::max<size_t>(cells.size(), 1));
    // First guess of the reach: two mean cell spacings (Walter's r with w_r = 2).
    m_initial_radius = 2.0 * m_spacing;
    // No unfolding reaches farther than the sum of all triangles' diameters.
    for (sim::TriId t = 0; t < nt; ++t) m_max_radius += 2 * crps.frame(t).bound_radius;

    // --- Per triangle, in parallel; then concatenated in triangle order ---
    // Both layouts: [0] coarse regions (few, long lists), [1] fine (as many regions as
    // cell spacings across, up to 3 per side).
    std::vector<std::array<Built, 2>> built(nt);
    struct Scratch {
        sim::UnfoldScratch unfold;
        std::vector<sim::UnfoldedTriangle> unfolded;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 64), [&](const auto &range) {
        Scratch &s = scratch.local();
        for (size_t t = range.begin(); t != range.end(); ++t)
            build_triangle(crps, static_cast<sim::TriId>(t), s.unfold, s.unfolded,
                           built[t]);
    });

    // Fine regions scan fewer cells, coarse ones need less memory: fine while the whole
    // index stays within the budget (then it mostly stays in cache anyway).
    size_t blocks_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) blocks_of_layout[l] += b[l].blocks.size();
    size_t regions_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) regions_of_layout[l] += b[l].regions * b[l].regions;
    const size_t fixed = nt * sizeof(Frame) + (nt + 1) * sizeof(uint32_t) +
                         (regions_of_layout[1] + 1) * sizeof(uint32_t);
    const int layout =
        fixed + blocks_of_layout[1] * sizeof(Block) <= m_options.fine_regions_max_bytes;
    m_stats.fine_regions = layout == 1;
    size_t total_blocks = blocks_of_layout[layout], lists = 0, entries = 0, distinct = 0;
    if (total_blocks >= (size_t(1) << 30))
        throw std::length_error("closest-cell index: more than 2^30 candidate blocks");
    m_frames.resize(nt);
    m_first_region.resize(nt + 1);
    m_region_block.reserve(regions_of_layout[layout] + 1);
    m_blocks.reserve(total_blocks);
    for (size_t t = 0; t < nt; ++t) {
        Built &b = built[t][layout];
        m_frames[t] = b.frame;
        m_first_region[t] = static_cast<uint32_t>(m_region_block.size()) << 2 | b.regions;
        const uint32_t first = static_cast<uint32_t>(m_blocks.size());
        for (uint32_t k = 0; k < b.regions * b.regions; ++k)
            m_region_block.push_back(first + (k ? b.end[k - 1] : 0));
        m_blocks.insert(m_blocks.end(), b.blocks.begin(), b.blocks.end());
        m_stats.triangles_without_cells_in_reach += b.entries == 0;
        m_stats.triangles_with_regions += b.regions > 1;
        m_stats.max_candidate_cells = std::max(m_stats.max_candidate_cells, b.longest);
        lists += b.regions * b.regions;
        entries += b.entries;
        distinct += b.distinct_triangles;
        built[t] = {};
    }
    m_first_region[nt] = static_cast<uint32_t>(m_region_block.size()) << 2 | 1;
    m_region_block.push_back(static_cast<uint32_t>(m_blocks.size()));
    m_stats.mean_candidates = lists ? double(distinct) / lists : 0;
    m_stats.mean_candidate_cells = lists ? double(entries) / lists : 0;
    m_stats.bytes = m_frames.size() * sizeof(Frame) +
                    m_first_region.size() * sizeof(uint32_t) +
                    m_region_block.size() * sizeof(uint32_t) +
                    m_blocks.size() * sizeof(Block);
    m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void ClosestCellIndex::build_triangle(const sim::Crps &crps, sim::TriId t,
                                      sim::UnfoldScratch &scratch,
                                      std::vector<sim::UnfoldedTriangle> &unfolded,
                                      std::array<Built, 2> &out) const {
    const CellTable &cells = *m_cells;
    const sim::CrpsFrame &ft = crps.frame(t);

    // --- Subdivisions: r regions per side searched at run time, n per side built ---
    // Fine regions: about one per cell spacing across (the per-sub-triangle lists of
    // before). Coarse ones: one list per triangle while the triangle is at most six
    // cell spacings across (on the cow with 20 000 cells, 78 % of the triangles), as its
    // sub-triangles' lists overlap so much that storing them apart costs more cache
    // misses than their shorter scans save (a threshold of four spacings: 4.3 MB on the
    // cow, no faster). The reach is computed per sub-triangle of a finer n-subdivision
    // (about two per cell spacing, at most 6, nested in both r-subdivisions): finer
    // sub-triangles have tighter radii R_S, so the lists are shorter (one list per
    // triangle on the cow: 28.8 cells with n <= 3, 21.9 with n <= 6), at no cost to a
    // lookup.
    const double spacings = 2 * ft.bound_radius / std::max(m_spacing, 1e-300);
    const uint32_t r_max =
        std::clamp<uint32_t>(m_options.max_subdivision, 1, max_subdivision);
    const uint32_t rs[2] = {
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings / 6)), 1, r_max),
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings)), 1, r_max)};
    // n: about two per spacing, at most 6, a multiple of both r (lcm(r0, r1) <= 6).
    const uint32_t lcm = rs[0] * rs[1] / std::gcd(rs[0], rs[1]);
    const uint32_t fine =
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(2 * spacings)), 1, 6);
    const uint32_t n = lcm * ((fine + lcm - 1) / lcm);
    const sim::Vec2d v0 = ft.v[0], e1 = ft.v[1] - ft.v[0], e2 = ft.v[2] - ft.v[0];
    {
        Frame &f = out[0].frame;
        f = {float(v0.x), float(v0.y), float(e1.x), float(e1.y), float(e2.x), float(e2.y), 0};
        f.inv_det = 1.0f / (f.e1x * f.e2y - f.e1y * f.e2x);  // in float, as it always was
        out[1].frame = f;
    }
    struct Sub {
        uint32_t region[2];  // the sub-triangles of the r-subdivisions holding this one
        sim::Vec2d v[3], centre;
        double bound = 0, reach_needed = 0;
    };
    std::vector<Sub> subs;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; i + j < n; ++j)
            for (int upper = 0; upper < 2; ++upper) {
                if (upper && i + j + 1 >= n) continue;
                Sub s;
                const auto b = sub_triangle(n, i, j, upper);
                for (int c = 0; c < 3; ++c) s.v[c] = v0 + e1 * b[c][0] + e2 * b[c][1];
                s.centre = (s.v[0] + s.v[1] + s.v[2]) / 3.0;
                for (int c = 0; c < 3; ++c)
                    s.bound = std::max(s.bound, length(s.v[c] - s.centre));
                for (int l = 0; l < 2; ++l)
                    s.region[l] = slot_at(rs[l], (b[0][0] + b[1][0] + b[2][0]) / 3,
                                          (b[0][1] + b[1][1] + b[2][1]) / 3);
                subs.push_back(s);
            }

    // --- Grow t's unfolding until it holds, for every S, all cells within R_S of S ---
    // Every cell of the unfolding carried into t's frame once (Teo's F[j→t]), in double.
    // When fewer than three cells are reachable the radius doubles up to the size of the
    // whole surface, after which the lists hold whatever there is (possibly nothing).
    struct Mapped {
        sim::Vec2d p;
        uint32_t cell;
        sim::TriId tri;
    };
    std::vector<Mapped> mapped;
    double radius = m_initial_radius + ft.bound_radius;
    for (int iteration = 0; iteration < 64; ++iteration) {
        sim::unfold_around_triangle(crps, t, radius, unfolded, scratch, m_options.paths);
        mapped.clear();
        for (const sim::UnfoldedTriangle &u : unfolded)
            for (uint32_t k = cells.row[u.tri]; k < cells.row[u.tri + 1]; ++k)
                mapped.push_back({u.to_master.apply({cells.x[k], cells.z[k]}), k, u.tri});
        double needed = 0;
        for (Sub &s : subs) {
            // For any three cells T, F3(q) <= max_{c in T} |q - c| on all of S, and that
            // maximum over the triangle S is reached at one of its corners. T = the three
            // nearest to S's centroid or to one of its corners; the tightest bound wins.
            // (It is at most d_3 + b_S, the centroid bound.)
            s.reach_needed = inf;
            const sim::Vec2d probes[4] = {s.centre, s.v[0], s.v[1], s.v[2]};
            for (const sim::Vec2d &probe : probes) {
                const Mapped *near[3] = {nullptr, nullptr, nullptr};
                double d[3] = {inf, inf, inf};
                for (const Mapped &m : mapped) {
                    const double dk = length(m.p - probe);
                    if (dk < d[2]) {
                        d[2] = dk;
                        near[2] = &m;
                        if (d[2] < d[1])
                            std::swap(d[1], d[2]), std::swap(near[1], near[2]);
                        if (d[1] < d[0])
                            std::swap(d[0], d[1]), std::swap(near[0], near[1]);
                    }
                }
                if (!near[2]) continue;  // fewer than three cells within the radius
                double reach = 0;
                for (const Mapped *m : near)
                    for (const sim::Vec2d &corner : s.v)
                        reach = std::max(reach, length(m->p - corner));
                s.reach_needed = std::min(s.reach_needed, reach);
            }
            needed = std::max(needed, s.reach_needed);
        }
        if (needed <= radius || radius >= m_max_radius) break;
        // A larger radius may reach triangles by other paths: grow with a margin,
        // re-check.
        radius = std::isfinite(needed) ? std::min(needed * 1.0001 + 1e-12, m_max_radius)
                                       : std::min(2 * radius, m_max_radius);
    }

    // --- Per region: the cells within R_S of one of its S, by distance from it ---
    // (Each triangle occurs once in an unfolding, so each cell once in `mapped`.)
    struct Entry {
        double bound;
        const Mapped *m;
    };
    std::vector<Entry> list;
    std::vector<sim::TriId> tris;
    for (int layout = 0; layout < 2; ++layout) {
        Built &o = out[layout];
        const uint32_t r = rs[layout];
        o.regions = r;
        if (layout == 1 && rs[1] == rs[0]) {  // the same lists
            o = out[0];
            break;
        }
        std::array<std::array<sim::Vec2d, 3>, max_subdivision * max_subdivision> regions;
        for (uint32_t i = 0; i < r; ++i)
            for (uint32_t j = 0; i + j < r; ++j)
                for (int upper = 0; upper < 2; ++upper) {
                    if (upper && i + j + 1 >= r) continue;
                    const auto b = sub_triangle(r, i, j, upper);
                    for (int c = 0; c < 3; ++c)
                        regions[slot_index(r, i, j, upper)][c] =
                            v0 + e1 * b[c][0] + e2 * b[c][1];
                }
        for (uint32_t k = 0; k < r * r; ++k) {
            const std::array<sim::Vec2d, 3> &region = regions[k];
            list.clear();
            for (const Mapped &m : mapped)
                for (const Sub &s : subs)
                    // (The distance from S is at least that from its centre less its
                    // radius: a cheap test first, with room for its rounding.)
                    if (s.region[layout] == k &&
                        length(m.p - s.centre) - s.bound <= s.reach_needed * (1 + 1e-6) &&
                        sim::point_triangle_distance(m.p, s.v) <=
                            s.reach_needed * (1 + 1e-9)) {
                        list.push_back(
                            {sim::point_triangle_distance(m.p, region.data()), &m});
                        break;
                    }
            std::sort(list.begin(), list.end(), [](const Entry &a, const Entry &b) {
                return a.bound < b.bound || (a.bound == b.bound && a.m->cell < b.m->cell);
            });
            tris.clear();
            for (const Entry &e : list) tris.push_back(e.m->tri);
            std::sort(tris.begin(), tris.end());
            o.distinct_triangles += std::unique(tris.begin(), tris.end()) - tris.begin();
            o.entries += list.size();
            o.longest = std::max(o.longest, list.size());
            for (size_t i = 0; i < list.size(); i += per_block) {
                Block b;
                // The bound is rounded down by more than float's error in the scan's
                // distances (positions of size |p| + the triangle's radius), so rounding
                // never prunes the true nearest.
                const double margin =
                    1e-5 * (list[i].bound + length(list[i].m->p) + ft.bound_radius);
                const double lower = std::max(0.0, list[i].bound - margin);
                b.bound2 = float(lower * lower * (1 - 1e-6));
                for (size_t l = 0; l < per_block; ++l) {
                    const bool real = i + l < list.size();
                    b.x[l] = real ? float(list[i + l].m->p.x) : inf_f;
                    b.y[l] = real ? float(list[i + l].m->p.y) : inf_f;
                    b.cell[l] = real ? list[i + l].m->cell : ClosestCell::none;
                }
                o.blocks.push_back(b);
            }
            o.end[k] = static_cast<uint32_t>(o.blocks.size());
        }
    }
}

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
