// Implements Teo 2006 §6.2 (see closest_cell.h).
#include "shader/clonal_mosaic/closest_cell.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace pelage::shader {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr uint32_t max_subdivision = 3;

// The barycentric (b1, b2) corners of sub-triangle (i, j, upper) of an n-subdivision.
std::array<std::array<double, 2>, 3> sub_triangle(uint32_t n, uint32_t i, uint32_t j, bool upper) {
    const double s = 1.0 / n;
    if (upper) return {{{(i + 1) * s, j * s}, {(i + 1) * s, (j + 1) * s}, {i * s, (j + 1) * s}}};
    return {{{i * s, j * s}, {(i + 1) * s, j * s}, {i * s, (j + 1) * s}}};
}

}  // namespace

struct ClosestCellIndex::Built {
    TriangleRegions regions{};
    std::vector<uint32_t> slot_sizes;  // 2n² slots
    std::vector<Candidate> candidates;
    std::vector<sim::TriId> candidate_tri;
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
            build_triangle(crps, static_cast<sim::TriId>(t), s.unfold, s.unfolded, built[t]);
    });

    m_regions.resize(nt);
    m_slot_row.assign(1, 0);
    size_t used_slots = 0, cand_cells = 0;
    for (size_t t = 0; t < nt; ++t) {
        Built &b = built[t];
        b.regions.first_slot = static_cast<uint32_t>(m_slot_row.size() - 1);
        m_regions[t] = b.regions;
        for (uint32_t size : b.slot_sizes) {
            m_slot_row.push_back(m_slot_row.back() + size);
            used_slots += size > 0;
        }
        for (const Candidate &c : b.candidates) cand_cells += c.end - c.begin;
        m_candidates.insert(m_candidates.end(), b.candidates.begin(), b.candidates.end());
        m_candidate_tri.insert(m_candidate_tri.end(), b.candidate_tri.begin(), b.candidate_tri.end());
        m_stats.triangles_without_cells_in_reach += b.candidates.empty();
        b = Built{};
    }
    m_stats.mean_candidates = used_slots ? double(m_candidates.size()) / used_slots : 0;
    m_stats.mean_candidate_cells = used_slots ? double(cand_cells) / used_slots : 0;
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
        static_cast<uint32_t>(std::ceil(2 * ft.bound_radius / std::max(m_spacing, 1e-300))), 1,
        max_subdivision);
    const sim::Vec2d v0 = ft.v[0], e1 = ft.v[1] - ft.v[0], e2 = ft.v[2] - ft.v[0];
    const double det = cross(e1, e2);
    out.regions = {float(v0.x), float(v0.y), float(e2.y / det), float(-e2.x / det),
                   float(-e1.y / det), float(e1.x / det), n, 0};
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
                s.slot = (i * n + j) * 2 + upper;
                const auto b = sub_triangle(n, i, j, upper);
                for (int c = 0; c < 3; ++c) s.v[c] = v0 + e1 * b[c][0] + e2 * b[c][1];
                s.centre = (s.v[0] + s.v[1] + s.v[2]) / 3.0;
                for (int c = 0; c < 3; ++c) s.bound = std::max(s.bound, length(s.v[c] - s.centre));
                subs.push_back(s);
            }

    // --- Grow t's unfolding until it holds, for every S, all cells within R_S of S ---
    // When fewer than two cells are reachable the radius doubles up to the size of the
    // whole surface, after which the lists hold whatever there is (possibly nothing).
    double radius = m_initial_radius + ft.bound_radius;
    for (int iteration = 0; iteration < 64; ++iteration) {
        sim::unfold_around_triangle(crps, t, radius, unfolded, scratch, m_options.paths);
        double needed = 0;
        for (Sub &s : subs) {
            // Distances to the three nearest cells: lists serve searches for up to three.
            double d[3] = {inf, inf, inf};
            for (const sim::UnfoldedTriangle &u : unfolded)
                for (uint32_t k = cells.row[u.tri]; k < cells.row[u.tri + 1]; ++k) {
                    const double dk = length(u.to_master.apply({cells.x[k], cells.z[k]}) - s.centre);
                    if (dk < d[2]) {
                        d[2] = dk;
                        if (d[2] < d[1]) std::swap(d[1], d[2]);
                        if (d[1] < d[0]) std::swap(d[0], d[1]);
                    }
                }
            s.reach_needed = d[2] + s.bound;
            needed = std::max(needed, s.reach_needed);
        }
        if (needed <= radius || radius >= m_max_radius) break;
        // A larger radius may reach triangles by other paths: grow with a margin, re-check.
        radius = std::isfinite(needed) ? std::min(needed * 1.0001 + 1e-12, m_max_radius)
                                       : std::min(2 * radius, m_max_radius);
    }

    // --- Per sub-triangle: the triangles holding cells within R_S, nearest first ---
    out.slot_sizes.assign(2 * n * n, 0);
    std::vector<std::pair<double, size_t>> order;  // (gap, index into unfolded)
    std::vector<sim::Vec2d> mapped(3 * unfolded.size());
    for (size_t u = 0; u < unfolded.size(); ++u)
        for (int c = 0; c < 3; ++c)
            mapped[3 * u + c] = unfolded[u].to_master.apply(crps.frame(unfolded[u].tri).v[c]);
    std::sort(subs.begin(), subs.end(), [](const Sub &a, const Sub &b) { return a.slot < b.slot; });
    for (const Sub &s : subs) {
        order.clear();
        for (size_t u = 0; u < unfolded.size(); ++u) {
            if (cells.count_on(unfolded[u].tri) == 0) continue;
            const double gap = sim::triangle_triangle_distance(s.v, &mapped[3 * u]);
            if (gap <= s.reach_needed * (1 + 1e-9)) order.push_back({gap, u});
        }
        std::stable_sort(order.begin(), order.end(),
                         [](const auto &a, const auto &b) { return a.first < b.first; });
        out.slot_sizes[s.slot] = static_cast<uint32_t>(order.size());
        for (const auto &[gap, u] : order) {
            const sim::TriId j = unfolded[u].tri;
            const uint32_t begin = cells.row[j], end = cells.row[j + 1];
            float reach = 0;
            for (uint32_t k = begin; k < end; ++k)
                reach = std::max(reach, std::sqrt(cells.x[k] * cells.x[k] + cells.z[k] * cells.z[k]));
            const sim::RigidMap2 to_j = unfolded[u].to_master.inverse();
            // Round the bounds outward so float rounding can never prune the true nearest.
            out.candidates.push_back({float(to_j.c), float(to_j.s), float(to_j.ax), float(to_j.ay),
                                      begin, end, reach * (1 + 1e-5f) + 1e-30f,
                                      float(gap) * (1 - 1e-5f)});
            out.candidate_tri.push_back(j);
        }
    }
    // Slots are laid out in slot order; the candidates above were appended in the same
    // order because `subs` is sorted by slot and unused slots are empty.
}

uint32_t ClosestCellIndex::slot_of(sim::TriId t, Vec2f q) const {
    const TriangleRegions &r = m_regions[t];
    const float dx = q.x - r.v0x, dy = q.y - r.v0y;
    const float nf = float(r.n);
    // Clamp to the triangle: hits may sit a rounding error outside it.
    const float u = std::clamp((r.i00 * dx + r.i01 * dy) * nf, 0.0f, nf);
    const float v = std::clamp((r.i10 * dx + r.i11 * dy) * nf, 0.0f, nf - u);
    uint32_t i = std::min(uint32_t(u), r.n - 1), j = std::min(uint32_t(v), r.n - 1);
    bool upper = (u - float(i)) + (v - float(j)) > 1.0f;
    if (i + j >= r.n - 1) {  // the last row of sub-triangles has no upper halves
        j = r.n - 1 - std::min(i, r.n - 1);
        upper = false;
    }
    return r.first_slot + (i * r.n + j) * 2 + (upper ? 1 : 0);
}

template <bool prune, int K>
void ClosestCellIndex::scan(uint32_t slot, Vec2f q, Nearest<K> &n) const {
    const float *x = m_cells->x.data(), *z = m_cells->z.data();
    const uint32_t *id = m_cells->id.data();
    // D_min of Teo Fig. 6.2: the radius beyond which no cell matters any more — the
    // distance to the K-th nearest found so far.
    float d_min = std::sqrt(n.d2[K - 1]);
    for (uint32_t k = m_slot_row[slot]; k < m_slot_row[slot + 1]; ++k) {
        const Candidate &c = m_candidates[k];
        if constexpr (prune) {
            // Candidates are sorted by their distance from the sub-triangle: none further
            // can enter the K nearest.
            if (c.gap > d_min) break;
        }
        // Reverse neighbour mapping: the query into j's frame, 4 mul + 4 add.
        const float qx = c.c * q.x - c.s * q.y + c.ax;
        const float qz = c.s * q.x + c.c * q.y + c.ay;
        if constexpr (prune) {
            // j's cells lie within `reach` of its centroid (the origin of its frame).
            const float r = c.reach + d_min;
            if (qx * qx + qz * qz > r * r) continue;
        }
        bool changed = false;
        for (uint32_t i = c.begin; i < c.end; ++i) {
            const float dx = x[i] - qx, dz = z[i] - qz;
            const float d2 = dx * dx + dz * dz;
            if (d2 > n.d2[K - 1]) continue;  // the common case
            // Order by (distance, stable id); a cell listed twice (exhaustive scan of
            // several sub-triangles) enters once.
            int pos = K;
            bool seen = false;
            for (int j = K - 1; j >= 0; --j) {
                seen |= n.index[j] == i;
                if (d2 < n.d2[j] || (d2 == n.d2[j] && n.index[j] != ClosestCell::none && id[i] < id[n.index[j]]))
                    pos = j;
            }
            if (seen || pos == K) continue;
            for (int j = K - 1; j > pos; --j) {
                n.d2[j] = n.d2[j - 1];
                n.index[j] = n.index[j - 1];
            }
            n.d2[pos] = d2;
            n.index[pos] = i;
            changed = true;
        }
        if (changed) d_min = std::sqrt(n.d2[K - 1]);
    }
}

ClosestCell ClosestCellIndex::find(sim::TriId t, Vec2f q) const {
    Nearest<2> n;
    scan<true, 2>(slot_of(t, q), q, n);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

ClosestCell ClosestCellIndex::find_nearest(sim::TriId t, Vec2f q) const {
    Nearest<1> n;
    scan<true, 1>(slot_of(t, q), q, n);
    return {n.index[0], ClosestCell::none, std::sqrt(n.d2[0]), std::numeric_limits<float>::infinity()};
}

ClosestCellIndex::Nearest<3> ClosestCellIndex::find_three(sim::TriId t, Vec2f q) const {
    Nearest<3> n;
    scan<true, 3>(slot_of(t, q), q, n);
    return n;
}

ClosestCell ClosestCellIndex::find_exhaustive(sim::TriId t, Vec2f q) const {
    Nearest<2> n;
    const TriangleRegions &r = m_regions[t];
    for (uint32_t s = 0; s < 2 * r.n * r.n; ++s) scan<false, 2>(r.first_slot + s, q, n);
    return {n.index[0], n.index[1], std::sqrt(n.d2[0]), std::sqrt(n.d2[1])};
}

float ClosestCellIndex::distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const {
    const uint32_t slot = slot_of(t, q);
    for (uint32_t k = m_slot_row[slot]; k < m_slot_row[slot + 1]; ++k) {
        const Candidate &c = m_candidates[k];
        if (cell < c.begin || cell >= c.end) continue;
        const float qx = c.c * q.x - c.s * q.y + c.ax, qz = c.s * q.x + c.c * q.y + c.ay;
        return std::hypot(m_cells->x[cell] - qx, m_cells->z[cell] - qz);
    }
    return std::numeric_limits<float>::infinity();
}

}  // namespace pelage::shader
