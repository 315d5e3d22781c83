// Implements Teo 2006 §6.2 (see closest_cell.h).
#include "shader/clonal_mosaic/closest_cell.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pelage::shader {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr float inf_f = std::numeric_limits<float>::infinity();

// The barycentric (b1, b2) corners of sub-triangle (i, j, upper) of an n-subdivision.
std::array<std::array<double, 2>, 3> sub_triangle(uint32_t n, uint32_t i, uint32_t j,
                                                  bool upper) {
    const double s = 1.0 / n;
    if (upper)
        return {{{(i + 1) * s, j * s}, {(i + 1) * s, (j + 1) * s}, {i * s, (j + 1) * s}}};
    return {{{i * s, j * s}, {(i + 1) * s, j * s}, {i * s, (j + 1) * s}}};
}

// Sub-triangles of an n-subdivision numbered row by row: row i holds n - i lower and
// n - i - 1 upper ones, interleaved, so the n² of them are 0 … n² - 1.
uint32_t slot_index(uint32_t n, uint32_t i, uint32_t j, bool upper) {
    return i * (2 * n - i) + 2 * j + (upper ? 1 : 0);
}

// Position of grid point (x, y) (16 bits each) along a Hilbert curve over the grid: points
// close along the curve are close in the plane. (The usual iterative conversion from
// (x, y) to distance, quadrant by quadrant; Warren, "Hacker's Delight", 2nd ed., ch. 16.)
uint64_t hilbert_index(uint32_t x, uint32_t y) {
    constexpr uint32_t side = 1u << 16;
    uint64_t d = 0;
    for (uint32_t s = side / 2; s > 0; s /= 2) {
        const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
        d += uint64_t(s) * s * ((3 * rx) ^ ry);
        if (ry == 0) {  // rotate the quadrant
            if (rx == 1) {
                x = side - 1 - x;
                y = side - 1 - y;
            }
            std::swap(x, y);
        }
    }
    return d;
}

}  // namespace

struct ClosestCellIndex::Built {
    std::vector<Line> lines;  // header, visits, union blocks
    size_t entries = 0, distinct_triangles = 0, used_slots = 0, union_cells = 0;
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
    std::vector<Built> built(nt);
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

    size_t total_lines = 0, used_slots = 0, entries = 0, distinct = 0, unions = 0;
    for (const Built &b : built) total_lines += b.lines.size();
    if (total_lines >= (size_t(1) << 32))
        throw std::length_error("closest-cell index: more than 2^32 lines");
    m_runs.resize(nt);
    m_lines.reserve(total_lines);
    for (size_t t = 0; t < nt; ++t) {
        Built &b = built[t];
        m_runs[t] = static_cast<uint32_t>(m_lines.size());
        m_lines.insert(m_lines.end(), b.lines.begin(), b.lines.end());
        m_stats.triangles_without_cells_in_reach += b.entries == 0;
        m_stats.max_union_cells = std::max(m_stats.max_union_cells, b.union_cells);
        used_slots += b.used_slots;
        entries += b.entries;
        distinct += b.distinct_triangles;
        unions += b.union_cells;
        b = Built{};
    }
    m_stats.mean_candidates = used_slots ? double(distinct) / used_slots : 0;
    m_stats.mean_candidate_cells = used_slots ? double(entries) / used_slots : 0;
    m_stats.mean_union_cells = nt ? double(unions) / nt : 0;
    m_stats.bytes = m_runs.size() * sizeof(uint32_t) + m_lines.size() * sizeof(Line);
    m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void ClosestCellIndex::build_triangle(const sim::Crps &crps, sim::TriId t,
                                      sim::UnfoldScratch &scratch,
                                      std::vector<sim::UnfoldedTriangle> &unfolded,
                                      Built &out) const {
    const CellTable &cells = *m_cells;
    const sim::CrpsFrame &ft = crps.frame(t);

    // --- Subdivision: about one sub-triangle per cell spacing across, at most 3 ---
    const uint32_t n = std::clamp<uint32_t>(
        static_cast<uint32_t>(
            std::ceil(2 * ft.bound_radius / std::max(m_spacing, 1e-300))),
        1, std::clamp<uint32_t>(m_options.max_subdivision, 1, max_subdivision));
    const sim::Vec2d v0 = ft.v[0], e1 = ft.v[1] - ft.v[0], e2 = ft.v[2] - ft.v[0];
    struct Sub {
        uint32_t slot;
        sim::Vec2d v[3], centre;
        double bound = 0, reach_needed = 0;
    };
    std::vector<Sub> subs;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; i + j < n; ++j)
            for (int upper = 0; upper < 2; ++upper) {
                if (upper && i + j + 1 >= n) continue;
                Sub s;
                s.slot = slot_index(n, i, j, upper);
                const auto b = sub_triangle(n, i, j, upper);
                for (int c = 0; c < 3; ++c) s.v[c] = v0 + e1 * b[c][0] + e2 * b[c][1];
                s.centre = (s.v[0] + s.v[1] + s.v[2]) / 3.0;
                for (int c = 0; c < 3; ++c)
                    s.bound = std::max(s.bound, length(s.v[c] - s.centre));
                subs.push_back(s);
            }
    std::sort(subs.begin(), subs.end(),
              [](const Sub &a, const Sub &b) { return a.slot < b.slot; });

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

    // --- Per sub-triangle: the cells within R_S of S (bit S of `in_list`) ---
    // Each triangle occurs once in an unfolding, so each cell once in `mapped`.
    std::vector<uint16_t> in_list(mapped.size(), 0);
    std::vector<sim::TriId> tris;
    for (const Sub &s : subs) {
        tris.clear();
        for (size_t i = 0; i < mapped.size(); ++i)
            if (sim::point_triangle_distance(mapped[i].p, s.v) <=
                s.reach_needed * (1 + 1e-9)) {
                in_list[i] |= uint16_t(1u << s.slot);
                tris.push_back(mapped[i].tri);
            }
        out.entries += tris.size();
        out.used_slots += 1;
        std::sort(tris.begin(), tris.end());
        out.distinct_triangles += std::unique(tris.begin(), tris.end()) - tris.begin();
    }

    // --- Their union, once, in Hilbert-curve order: each block five nearby cells ---
    // A sub-triangle's list then fills few blocks, mostly with its own cells.
    std::vector<uint32_t> members;  // into mapped
    sim::Vec2d lo{inf, inf}, hi{-inf, -inf};
    for (uint32_t i = 0; i < mapped.size(); ++i) {
        if (!in_list[i]) continue;
        members.push_back(i);
        lo = {std::min(lo.x, mapped[i].p.x), std::min(lo.y, mapped[i].p.y)};
        hi = {std::max(hi.x, mapped[i].p.x), std::max(hi.y, mapped[i].p.y)};
    }
    const double cell_size = std::max(std::max(hi.x - lo.x, hi.y - lo.y), 1e-300) / 65535;
    std::vector<uint64_t> key(mapped.size());
    for (uint32_t i : members)
        key[i] = hilbert_index(uint32_t((mapped[i].p.x - lo.x) / cell_size),
                               uint32_t((mapped[i].p.y - lo.y) / cell_size));
    std::sort(members.begin(), members.end(), [&](uint32_t a, uint32_t b) {
        return key[a] < key[b] || (key[a] == key[b] && mapped[a].cell < mapped[b].cell);
    });
    out.union_cells = members.size();
    const size_t blocks = (members.size() + per_block - 1) / per_block;
    if (blocks > visit_max_blocks)
        throw std::length_error(
            "closest-cell index: " + std::to_string(members.size()) +
            " cells in reach of one triangle (at most " +
            std::to_string(visit_max_blocks * per_block) + "): use fewer cells");

    // --- Per sub-triangle: the blocks holding its cells, by their distance from it ---
    struct Visit {
        double bound;  // lower bound of the distance from S of the block's cells in S
        uint32_t block, mask;
    };
    std::vector<std::vector<Visit>> visits(subs.size());
    double max_bound = 0;
    for (const Sub &s : subs) {
        std::vector<Visit> &v = visits[s.slot];
        for (uint32_t b = 0; b < blocks; ++b) {
            Visit visit{inf, b, 0};
            for (uint32_t l = 0; l < per_block && b * per_block + l < members.size(); ++l) {
                const Mapped &m = mapped[members[b * per_block + l]];
                if (!(in_list[members[b * per_block + l]] >> s.slot & 1)) continue;
                visit.mask |= 1u << l;
                // Rounded down by more than float's error in the scan's distances
                // (positions of size |p| + the triangle's radius), so rounding never
                // prunes the true nearest.
                const double d = sim::point_triangle_distance(m.p, s.v);
                const double margin = 1e-5 * (d + length(m.p) + ft.bound_radius);
                visit.bound = std::min(visit.bound, std::max(0.0, d - margin));
            }
            if (!visit.mask) continue;
            max_bound = std::max(max_bound, visit.bound);
            v.push_back(visit);
        }
        std::sort(v.begin(), v.end(), [](const Visit &a, const Visit &b) {
            return a.bound < b.bound || (a.bound == b.bound && a.block < b.block);
        });
    }
    // Bounds are stored as multiples of `scale`, rounded down (a lower bound stays one).
    float scale = float(max_bound / visit_max_bound);
    if (double(scale) * visit_max_bound < max_bound)
        scale = std::nextafter(scale, inf_f);

    size_t total_visits = 0;
    for (const auto &v : visits) total_visits += v.size();
    const size_t visit_lines =
        (total_visits * sizeof(uint32_t) + sizeof(Line) - 1) / sizeof(Line);
    out.lines.assign(1 + visit_lines + blocks, Line{});
    Header h{};
    h.v0x = float(v0.x), h.v0y = float(v0.y), h.e1x = float(e1.x), h.e1y = float(e1.y);
    h.e2x = float(e2.x), h.e2y = float(e2.y), h.scale = scale;
    std::vector<uint32_t> packed;
    for (uint32_t k = 0; k < visits.size(); ++k) {
        for (const Visit &v : visits[k]) {
            const uint32_t q =
                scale > 0 ? uint32_t(std::min<double>(std::floor(v.bound / double(scale)),
                                                      visit_max_bound))
                          : 0;
            packed.push_back(q << (32 - visit_bound_bits) | v.block << per_block | v.mask);
        }
        h.end[k] = uint32_t(packed.size()) << 2;
    }
    h.end[0] |= n;
    std::memcpy(out.lines[1].bytes, packed.data(), packed.size() * sizeof(uint32_t));
    for (uint32_t b = 0; b < blocks; ++b) {
        Block block;
        for (uint32_t l = 0; l < per_block; ++l) {
            const bool real = b * per_block + l < members.size();
            const Mapped *m = real ? &mapped[members[b * per_block + l]] : nullptr;
            block.x[l] = real ? float(m->p.x) : inf_f;
            block.y[l] = real ? float(m->p.y) : inf_f;
            block.cell[l] = real ? m->cell : ClosestCell::none;
        }
        std::memcpy(out.lines[1 + visit_lines + b].bytes, &block, sizeof block);
    }
    std::memcpy(out.lines[0].bytes, &h, sizeof h);
}

ClosestCellIndex::Run ClosestCellIndex::run_at(sim::TriId t, float b1, float b2) const {
    const Line *first = &m_lines[m_runs[t]];
    const Header &h = *reinterpret_cast<const Header *>(first->bytes);
    const uint32_t n = h.end[0] & 3u;
    const float nf = float(n);
    // Clamp to the triangle: hits may sit a rounding error outside it.
    const float u = std::clamp(b1 * nf, 0.0f, nf);
    const float v = std::clamp(b2 * nf, 0.0f, nf - u);
    uint32_t i = std::min(uint32_t(u), n - 1), j = std::min(uint32_t(v), n - 1);
    bool upper = (u - float(i)) + (v - float(j)) > 1.0f;
    if (i + j >= n - 1) {  // the last row of sub-triangles has no upper halves
        j = n - 1 - std::min(i, n - 1);
        upper = false;
    }
    const uint32_t k = slot_index(n, i, j, upper);
    const uint32_t *visits = reinterpret_cast<const uint32_t *>(first + 1);
    const uint32_t total = h.end[n * n - 1] >> 2;
    const size_t visit_lines = (total * sizeof(uint32_t) + sizeof(Line) - 1) / sizeof(Line);
    return {visits + (k ? h.end[k - 1] >> 2 : 0), visits + (h.end[k] >> 2),
            reinterpret_cast<const Block *>(first + 1 + visit_lines), h.scale};
}

ClosestCellIndex::Run ClosestCellIndex::run_of(sim::TriId t, Vec2f q) const {
    // q's barycentric coordinates, by Cramer's rule on q - v0 = b1 e1 + b2 e2.
    const Header &r = header(t);
    const float dx = q.x - r.v0x, dy = q.y - r.v0y;
    const float inv_det = 1.0f / (r.e1x * r.e2y - r.e1y * r.e2x);
    return run_at(t, (dx * r.e2y - dy * r.e2x) * inv_det,
                  (r.e1x * dy - r.e1y * dx) * inv_det);
}

// True when a visit's cells, and all after it, lie beyond sqrt(d2): its bound (rounded
// down when stored) times the scale, squared, with a factor for the float rounding of
// this product and of the scan's own squared distances.
inline bool beyond(uint32_t bound, float scale, float d2) {
    const float lower = float(bound) * scale;
    return lower * lower * 0.999995f > d2;
}

template <int K>
void ClosestCellIndex::scan_block(const Block &b, uint32_t m, Vec2f q, Nearest<K> &n,
                                  float band, float &d_min2) const {
    // D_min² of Teo Fig. 6.2: beyond it no cell matters any more — the squared distance
    // to the K-th nearest found so far, or to F1 + band when that is nearer (band >= 0).
    float d2[per_block];
    for (int l = 0; l < per_block; ++l) {
        const float dx = b.x[l] - q.x, dy = b.y[l] - q.y;
        d2[l] = m >> l & 1 ? dx * dx + dy * dy : inf_f;
    }
    if (*std::min_element(d2, d2 + per_block) > d_min2) return;  // the common case
    const uint32_t *id = m_cells->id.data();
    for (int l = 0; l < per_block; ++l) {
        const uint32_t cell = b.cell[l];
        if (d2[l] > d_min2 || cell == ClosestCell::none) continue;
        // Order by (distance, stable id).
        int pos = K;
        for (int j = K - 1; j >= 0; --j)
            if (d2[l] < n.d2[j] || (d2[l] == n.d2[j] && n.index[j] != ClosestCell::none &&
                                    id[cell] < id[n.index[j]]))
                pos = j;
        if (pos == K) continue;
        for (int j = K - 1; j > pos; --j) {
            n.d2[j] = n.d2[j - 1];
            n.index[j] = n.index[j - 1];
        }
        n.d2[pos] = d2[l];
        n.index[pos] = cell;
        d_min2 = n.d2[K - 1];
        if (band >= 0) {
            const float cap = std::sqrt(n.d2[0]) + band;
            d_min2 = std::min(d_min2, cap * cap);
        }
    }
}

template <bool prune, int K>
void ClosestCellIndex::scan(const Run &r, Vec2f q, Nearest<K> &n, float band) const {
    float d_min2 = inf_f;
    for (const uint32_t *v = r.visit; v != r.visit_end; ++v) {
        // Visits are sorted by their cells' distance from the sub-triangle: once one
        // lies beyond D_min, so do all after it.
        if constexpr (prune)
            if (beyond(visit_bound(*v), r.scale, d_min2)) break;
        scan_block(r.blocks[visit_block(*v)], visit_mask(*v), q, n, band, d_min2);
    }
}

ClosestCell ClosestCellIndex::find(sim::TriId t, Vec2f q) const {
    Nearest<2> n;
    scan<true, 2>(run_of(t, q), q, n);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, Vec2f q) const {
    Nearest<1> n;
    scan<true, 1>(run_of(t, q), q, n);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three(sim::TriId t, Vec2f q) const {
    Nearest<3> n;
    scan<true, 3>(run_of(t, q), q, n);
    return n;
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, Vec2f q,
                                                                 float band) const {
    return three_within(run_of(t, q), q, band);
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::three_within(const Run &r, Vec2f q,
                                                            float band) const {
    // Two passes over the same (by then cached) blocks: the nearest cell with the
    // hardest pruning, then whatever else lies within F1 + band — mostly nothing, so most
    // hits cost about one nearest-cell search. The result is what one three-nearest scan
    // cut at F1 + band gives (the second pass keeps the same (distance, id) order).
    Nearest<1> first;
    scan<true, 1>(r, q, first);
    Nearest<3> n;
    n.d2[0] = first.d2[0];
    n.index[0] = first.index[0];
    if (first.index[0] == ClosestCell::none) return n;
    const float cap = std::sqrt(first.d2[0]) + std::max(band, 0.0f);
    const float cap2 = cap * cap;
    const uint32_t *id = m_cells->id.data();
    for (const uint32_t *v = r.visit; v != r.visit_end; ++v) {
        if (beyond(visit_bound(*v), r.scale, cap2)) break;
        const Block &b = r.blocks[visit_block(*v)];
        const uint32_t m = visit_mask(*v);
        float d2[per_block];
        for (int l = 0; l < per_block; ++l) {
            const float dx = b.x[l] - q.x, dy = b.y[l] - q.y;
            d2[l] = m >> l & 1 ? dx * dx + dy * dy : inf_f;
        }
        if (*std::min_element(d2, d2 + per_block) > cap2) continue;
        for (int l = 0; l < per_block; ++l) {
            const uint32_t cell = b.cell[l];
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
    return n;
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, float b1, float b2) const {
    Nearest<1> n;
    const Vec2f q = point(t, b1, b2);
    scan<true, 1>(run_at(t, b1, b2), q, n);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]),
            std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three_within(sim::TriId t, float b1,
                                                                 float b2,
                                                                 float band) const {
    return three_within(run_at(t, b1, b2), point(t, b1, b2), band);
}

ClosestCell ClosestCellIndex::find_exhaustive(sim::TriId t, Vec2f q) const {
    // The whole union, unpruned: every cell of it is in some sub-triangle's list, once.
    Nearest<2> n;
    const Run r = run_of(t, q);
    // The run's blocks end where the next triangle's run begins.
    const size_t next = t + 1 < m_runs.size() ? m_runs[t + 1] : m_lines.size();
    const Block *end = reinterpret_cast<const Block *>(m_lines.data() + next);
    float d_min2 = inf_f;
    for (const Block *b = r.blocks; b != end; ++b)
        scan_block(*b, (1u << per_block) - 1, q, n, -1, d_min2);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

float ClosestCellIndex::distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const {
    const Run r = run_of(t, q);
    for (const uint32_t *v = r.visit; v != r.visit_end; ++v)
        for (int l = 0; l < per_block; ++l) {
            const Block &b = r.blocks[visit_block(*v)];
            if (visit_mask(*v) >> l & 1 && b.cell[l] == cell)
                return std::hypot(b.x[l] - q.x, b.y[l] - q.y);
        }
    return std::numeric_limits<float>::infinity();
}

}  // namespace pelage::shader
