#include "sim/mosaic/relaxation.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sim/core/random.h"
#include "sim/crps/unfold.h"

namespace pelage::sim {

void Neighbourhoods::update(const Crps &crps, double r) {
    const size_t nt = crps.num_triangles();
    if (m_entries.size() == nt && r <= m_radius && r * rebuild_ratio >= m_radius) return;
    const auto start = std::chrono::steady_clock::now();
    m_radius = r * slack;
    m_entries.assign(nt, {});
    m_bounding.resize(nt);
    for (TriId t = 0; t < nt; ++t) {
        const auto &v = crps.frame(t).v;
        m_bounding[t] = std::max({length(v[0]), length(v[1]), length(v[2])});
    }
    ++m_rebuilds;
    struct Scratch {
        UnfoldScratch visited;
        std::vector<std::pair<TriId, RigidMap2>> queue;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    const double R = m_radius;
    const Topology &topo = crps.topology();
    // Breadth-first unfolding as in sim/crps/unfold.h (first path wins, same order), with
    // cheap tests first: the centroid (origin of every 2D frame) of j mapped into t's
    // frame within R accepts; farther than R plus both bounding radii rejects; only the
    // cases in between pay for the exact triangle–triangle distance.
    tbb::parallel_for(
        tbb::blocked_range<TriId>(0, static_cast<TriId>(nt), 64), [&](const auto &range) {
            Scratch &s = scratch.local();
            s.visited.prepare(nt);
            for (TriId t = range.begin(); t != range.end(); ++t) {
                s.visited.begin();
                s.visited.visit(t);
                s.queue.clear();
                s.queue.push_back({t, RigidMap2{}});
                const Vec2d *vt = crps.frame(t).v.data();
                for (size_t head = 0; head < s.queue.size(); ++head) {
                    const auto [parent, Fp] = s.queue[head];
                    const auto nbrs = topo.neighbours(parent);
                    const auto maps = crps.to_master(parent);
                    for (size_t k = 0; k < nbrs.size(); ++k) {
                        const TriId j = nbrs[k];
                        if (!s.visited.visit(j)) continue;
                        const RigidMap2 F = compose(Fp, maps[k]);
                        const double dc =
                            std::hypot(F.ax, F.ay);  // F applied to j's centroid
                        bool accept = dc <= R;
                        if (!accept && dc <= R + m_bounding[t] + m_bounding[j]) {
                            const auto &vj = crps.frame(j).v;
                            const Vec2d mapped[3] = {F.apply(vj[0]), F.apply(vj[1]),
                                                     F.apply(vj[2])};
                            accept = triangle_triangle_distance(vt, mapped) <= R;
                        }
                        if (accept)
                            s.queue.push_back({j, F});
                        else
                            s.visited.unvisit(j);
                    }
                }
                auto &e = m_entries[t];
                e.reserve(s.queue.size());
                for (const auto &[j, F] : s.queue) e.push_back({j, F.inverse()});
            }
        });
    m_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

// Deterministic direction for two coincident cells (d = 0): a hashed angle of the pair,
// opposite for the two members so they separate (ties break on ids, never on memory
// order).
Vec2d tie_break_direction(uint64_t seed, CellId c, CellId p) {
    const CellId lo = std::min(c, p), hi = std::max(c, p);
    const uint64_t h = hash_counters(seed, static_cast<uint64_t>(RandomStream::tie_break),
                                     (uint64_t(lo) << 32) | hi);
    const double angle = double(h >> 11) * 0x1.0p-53 * 6.283185307179586;
    const Vec2d d{std::cos(angle), std::sin(angle)};
    return c == lo ? d : d * -1.0;
}

}  // namespace

RelaxStepResult Relaxer::step(const RelaxContext &ctx, Cells &cells,
                              const std::vector<TriId> &active) {
    m_nbhd.update(*ctx.crps, ctx.r);
    gather_by_triangle(cells, ctx.crps->num_triangles());
    size_moves(active);
    accumulate_forces(ctx, active);
    walk_moves(*ctx.crps, active);
    return apply_moves(cells, active);
}

// Cells into triangle order (parallel: each triangle fills its own range).
void Relaxer::gather_by_triangle(const Cells &cells, size_t nt) {
    m_row.resize(nt + 1);
    m_row[0] = 0;
    for (TriId t = 0; t < nt; ++t)
        m_row[t + 1] = m_row[t] + static_cast<uint32_t>(cells.on(t).size());
    const size_t n = m_row[nt];
    m_sx.resize(n);
    m_sz.resize(n);
    m_st.resize(n);
    m_sid.resize(n);
    {
        const double *xs = cells.x().data(), *zs = cells.z().data();
        const uint8_t *ts = cells.types().data();
        tbb::parallel_for(tbb::blocked_range<TriId>(0, static_cast<TriId>(nt), 256),
                          [&](const auto &range) {
                              for (TriId t = range.begin(); t != range.end(); ++t) {
                                  uint32_t i = m_row[t];
                                  for (CellId c : cells.on(t)) {
                                      m_sx[i] = xs[c];
                                      m_sz[i] = zs[c];
                                      m_st[i] = ts[c];
                                      m_sid[i] = c;
                                      ++i;
                                  }
                              }
                          });
    }
}

// Offsets of each active triangle's cells in the move buffer.
void Relaxer::size_moves(const std::vector<TriId> &active) {
    m_active_row.resize(active.size() + 1);
    m_active_row[0] = 0;
    for (size_t i = 0; i < active.size(); ++i)
        m_active_row[i + 1] = m_active_row[i] + (m_row[active[i] + 1] - m_row[active[i]]);
    const size_t n_active_cells = m_active_row.back();
    m_move.assign(n_active_cells, Vec2d{});
    m_dest.resize(n_active_cells);
}

// The displacement of every active cell (parallel over active triangles; each writes
// only its own cells).
void Relaxer::accumulate_forces(const RelaxContext &ctx,
                                const std::vector<TriId> &active) {
    const double r = ctx.r, r2 = r * r, inv_r = 1.0 / r;
    const double *xs = m_sx.data(), *zs = m_sz.data();
    const uint8_t *ts = m_st.data();
    const CellId *ids = m_sid.data();
    const bool aniso = ctx.field && !ctx.field->empty() && ctx.w_a > 0;
    const double iso_weight = (1.0 - ctx.w_a) * ctx.w_d;
    // 1 − α for every pair, resolved once per step (the initial phase uses one α).
    double one_minus_alpha[max_cell_types][max_cell_types];
    for (int c = 0; c < max_cell_types; ++c)
        for (int q = 0; q < max_cell_types; ++q)
            one_minus_alpha[c][q] = ctx.uniform_alpha
                                        ? 1.0 - ctx.alpha
                                        : (c < ctx.types->size() && q < ctx.types->size()
                                               ? ctx.types->one_minus_alpha(c, q)
                                               : 0.0);

    // --- Forces (parallel over active triangles; each writes only its own cells) ---
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, active.size(), 8), [&](const auto &range) {
            for (size_t ai = range.begin(); ai != range.end(); ++ai) {
                const TriId t = active[ai];
                const uint32_t mine_begin = m_row[t], mine_end = m_row[t + 1];
                if (mine_begin == mine_end) continue;
                Vec2d *D = m_move.data() + m_active_row[ai];
                for (const Neighbourhoods::Entry &e : m_nbhd.of(t)) {
                    const uint32_t theirs_begin = m_row[e.tri],
                                   theirs_end = m_row[e.tri + 1];
                    if (theirs_begin == theirs_end) continue;
                    const RigidMap2 &F = e.to_nbr;
                    // A cell farther than r from j's bounding circle has no neighbour on
                    // j.
                    const double reach = r + m_nbhd.bounding_radius(e.tri),
                                 reach2 = reach * reach;
                    for (uint32_t k = mine_begin; k < mine_end; ++k) {
                        const Vec2d q = F.apply({xs[k], zs[k]});  // C in j's frame
                        if (q.x * q.x + q.y * q.y > reach2) continue;
                        const double *oma_row = one_minus_alpha[ts[k]];
                        double sx = 0, sz = 0;
                        for (uint32_t p = theirs_begin; p < theirs_end; ++p) {
                            const double dx = q.x - xs[p], dz = q.y - zs[p];
                            const double d2 = dx * dx + dz * dz;
                            if (d2 >= r2 || p == k) continue;
                            // Walter 1998 Fig. 1 step 1: f = 1 − d/r, D = unit(C −
                            // P)·f·(1 − α)·r
                            const double oma = oma_row[ts[p]];
                            if (d2 > 0) {
                                const double d = std::sqrt(d2);
                                const double s = (1.0 - d * inv_r) * oma * r / d;
                                sx += dx * s;
                                sz += dz * s;
                            } else {
                                const Vec2d u =
                                    tie_break_direction(ctx.seed, ids[k], ids[p]);
                                sx += u.x * oma * r;
                                sz += u.y * oma * r;
                            }
                        }
                        // Back into t's frame: the rotation of F[j→t] is the inverse one.
                        Vec2d &Dk = D[k - mine_begin];
                        Dk.x += F.c * sx + F.s * sz;
                        Dk.y += -F.s * sx + F.c * sz;
                    }
                }
                // SG01 §3.2.1: C' = C + w_a·O + (1 − w_a)·w_d·D, O = (D·Â)·A
                for (uint32_t k = 0; k < mine_end - mine_begin; ++k) {
                    Vec2d m = D[k] * iso_weight;
                    if (aniso) {
                        const Vec2d A = ctx.field->a[t];
                        const double a2 = length_squared(A);
                        if (a2 > 0)
                            m += A * (ctx.w_a * dot(D[k], A) /
                                      std::sqrt(a2));  // |O| = (D·Â)|A|
                    }
                    D[k] = m;
                }
            }
        });
}

// Every moving cell walks across the surface (parallel, independent).
void Relaxer::walk_moves(const Crps &crps, const std::vector<TriId> &active) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, active.size(), 8), [&](const auto &range) {
            for (size_t ai = range.begin(); ai != range.end(); ++ai) {
                const uint32_t begin = m_row[active[ai]],
                               count = m_row[active[ai] + 1] - begin;
                for (uint32_t k = 0; k < count; ++k) {
                    const size_t i = m_active_row[ai] + k;
                    m_dest[i] =
                        walk(crps, {active[ai], {m_sx[begin + k], m_sz[begin + k]}},
                             m_move[i]);
                }
            }
        });
}

// Moves applied serially in triangle order, so bucket edits stay deterministic.
RelaxStepResult Relaxer::apply_moves(Cells &cells,
                                     const std::vector<TriId> &active) const {
    RelaxStepResult result;
    result.cells_moved = m_active_row.back();
    for (size_t ai = 0; ai < active.size(); ++ai) {
        const uint32_t begin = m_row[active[ai]], count = m_row[active[ai] + 1] - begin;
        for (uint32_t k = 0; k < count; ++k) {
            const size_t i = m_active_row[ai] + k;
            result.max_move = std::max(result.max_move, length(m_move[i]));
            cells.move(m_sid[begin + k], m_dest[i]);
        }
    }
    return result;
}

}  // namespace pelage::sim
