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

}  // namespace

ClosestCellIndex::ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                                   const ClosestCellOptions &options)
    : m_cells(&cells), m_options(options) {
    const auto t0 = std::chrono::steady_clock::now();
    const size_t nt = crps.num_triangles();
    double area = 0;
    for (sim::TriId t = 0; t < nt; ++t) area += crps.frame(t).area;
    // First guess of the reach: two mean cell spacings (Walter's r with w_r = 2).
    m_initial_radius = 2.0 * std::sqrt(area / std::max<size_t>(cells.size(), 1));
    // No unfolding reaches farther than the sum of all triangles' diameters.
    for (sim::TriId t = 0; t < nt; ++t) m_max_radius += 2 * crps.frame(t).bound_radius;

    // --- Candidate lists, built in parallel, then concatenated in triangle order ---
    std::vector<std::vector<Candidate>> per_tri(nt);
    std::vector<std::vector<sim::TriId>> per_tri_ids(nt);
    struct Scratch {
        sim::UnfoldScratch unfold;
        std::vector<sim::UnfoldedTriangle> unfolded;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 64), [&](const auto &range) {
        Scratch &s = scratch.local();
        for (size_t t = range.begin(); t != range.end(); ++t)
            build_candidates(crps, static_cast<sim::TriId>(t), s.unfold, s.unfolded, per_tri[t],
                             per_tri_ids[t]);
    });
    m_row.assign(nt + 1, 0);
    size_t cand_cells = 0;
    for (size_t t = 0; t < nt; ++t) {
        m_row[t + 1] = m_row[t] + static_cast<uint32_t>(per_tri[t].size());
        m_stats.triangles_without_cells_in_reach += per_tri[t].empty();
        for (const Candidate &c : per_tri[t]) cand_cells += c.end - c.begin;
    }
    m_candidates.reserve(m_row[nt]);
    m_candidate_tri.reserve(m_row[nt]);
    for (size_t t = 0; t < nt; ++t) {
        m_candidates.insert(m_candidates.end(), per_tri[t].begin(), per_tri[t].end());
        m_candidate_tri.insert(m_candidate_tri.end(), per_tri_ids[t].begin(), per_tri_ids[t].end());
    }
    m_stats.mean_candidates = nt ? double(m_candidates.size()) / nt : 0;
    m_stats.mean_candidate_cells = nt ? double(cand_cells) / nt : 0;
    m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void ClosestCellIndex::build_candidates(const sim::Crps &crps, sim::TriId t,
                                        sim::UnfoldScratch &scratch,
                                        std::vector<sim::UnfoldedTriangle> &unfolded,
                                        std::vector<Candidate> &out,
                                        std::vector<sim::TriId> &out_tri) const {
    const CellTable &cells = *m_cells;
    const double b_t = crps.frame(t).bound_radius;
    // Distances from t's centroid (the local origin) to the nearest and second-nearest
    // cells of an unfolding.
    auto two_nearest = [&](double *d1, double *d2) {
        *d1 = *d2 = inf;
        for (const sim::UnfoldedTriangle &u : unfolded)
            for (uint32_t k = cells.row[u.tri]; k < cells.row[u.tri + 1]; ++k) {
                const sim::Vec2d p = u.to_master.apply({cells.x[k], cells.z[k]});
                const double d = length(p);
                if (d < *d1) {
                    *d2 = *d1;
                    *d1 = d;
                } else if (d < *d2) {
                    *d2 = d;
                }
            }
    };

    // Grow the unfolding until it holds every cell within R_t = d_2 + b_t of t. The
    // second-nearest cell bounds F2 for any point q of t: F2(q) <= |q - c_2| <= d_2 + b_t.
    // When fewer than two cells are reachable the radius doubles up to the size of the
    // whole surface, after which the list holds whatever there is (possibly nothing).
    double radius = m_initial_radius + b_t;
    const double max_radius = m_max_radius;
    for (int iteration = 0; iteration < 64; ++iteration) {
        sim::unfold_around_triangle(crps, t, radius, unfolded, scratch, m_options.paths);
        double d1, d2;
        two_nearest(&d1, &d2);
        const double needed = d2 + b_t;
        if (needed <= radius) break;
        if (radius >= max_radius) break;
        // The unfolding may take other paths at a larger radius: grow with a margin and
        // check again.
        radius = std::isfinite(needed) ? std::min(needed * 1.0001 + 1e-12, max_radius)
                                       : std::min(2 * radius, max_radius);
    }

    // --- One candidate per triangle that holds cells, nearest first ---
    std::vector<std::pair<Candidate, sim::TriId>> list;
    for (const sim::UnfoldedTriangle &u : unfolded) {
        const uint32_t begin = cells.row[u.tri], end = cells.row[u.tri + 1];
        if (begin == end) continue;
        float reach = 0;
        for (uint32_t k = begin; k < end; ++k)
            reach = std::max(reach, std::sqrt(cells.x[k] * cells.x[k] + cells.z[k] * cells.z[k]));
        const sim::RigidMap2 to_j = u.to_master.inverse();
        // Round the bounds outward so float rounding can never prune the true nearest.
        list.push_back({{float(to_j.c), float(to_j.s), float(to_j.ax), float(to_j.ay), begin,
                         end, reach * (1 + 1e-5f), float(u.distance) * (1 - 1e-5f)},
                        u.tri});
    }
    std::stable_sort(list.begin(), list.end(),
                     [](const auto &a, const auto &b) { return a.first.gap < b.first.gap; });
    out.clear();
    out_tri.clear();
    for (const auto &[c, tri] : list) {
        out.push_back(c);
        out_tri.push_back(tri);
    }
}

float ClosestCellIndex::distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const {
    for (uint32_t k = m_row[t]; k < m_row[t + 1]; ++k) {
        const Candidate &c = m_candidates[k];
        if (cell < c.begin || cell >= c.end) continue;
        const float qx = c.c * q.x - c.s * q.y + c.ax, qz = c.s * q.x + c.c * q.y + c.ay;
        return std::hypot(m_cells->x[cell] - qx, m_cells->z[cell] - qz);
    }
    return std::numeric_limits<float>::infinity();
}

template <bool prune>
ClosestCell ClosestCellIndex::search(sim::TriId t, Vec2f q) const {
    const CellTable &cells = *m_cells;
    const float *x = cells.x.data(), *z = cells.z.data();
    const uint32_t *id = cells.id.data();
    float best_d2 = std::numeric_limits<float>::infinity(), second_d2 = best_d2;
    uint32_t best = ClosestCell::none;
    for (uint32_t k = m_row[t]; k < m_row[t + 1]; ++k) {
        const Candidate &c = m_candidates[k];
        if constexpr (prune) {
            // Candidates are sorted by their distance from t: none further can do better
            // than the current second-nearest (D_min, Teo Fig. 6.2).
            if (c.gap * c.gap > second_d2) break;
        }
        // Reverse neighbour mapping: the query into j's frame, 4 mul + 4 add.
        const float qx = c.c * q.x - c.s * q.y + c.ax;
        const float qz = c.s * q.x + c.c * q.y + c.ay;
        if constexpr (prune) {
            const float beyond = std::sqrt(qx * qx + qz * qz) - c.reach;
            if (beyond > 0 && beyond * beyond > second_d2) continue;
        }
        for (uint32_t i = c.begin; i < c.end; ++i) {
            const float dx = x[i] - qx, dz = z[i] - qz;
            const float d2 = dx * dx + dz * dz;
            if (d2 < best_d2 || (d2 == best_d2 && id[i] < id[best])) {
                second_d2 = best_d2;
                best_d2 = d2;
                best = i;
            } else if (d2 < second_d2) {
                second_d2 = d2;
            }
        }
    }
    return {best, std::sqrt(best_d2), std::sqrt(second_d2)};
}

template ClosestCell ClosestCellIndex::search<true>(sim::TriId, Vec2f) const;
template ClosestCell ClosestCellIndex::search<false>(sim::TriId, Vec2f) const;

}  // namespace pelage::shader
