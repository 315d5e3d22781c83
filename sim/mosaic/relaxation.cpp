#include "sim/mosaic/relaxation.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sim/core/random.h"
#include "sim/mosaic/pair_forces.h"

namespace pelage::sim {

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
    const auto start = std::chrono::steady_clock::now();
    accumulate_forces(ctx, active);
    m_force_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    walk_moves(*ctx.crps, active);
    return apply_moves(cells, active);
}

uint64_t Relaxer::interacting_pairs() const {
    uint64_t n = 0;
    for (const ForceScratch &s : m_force_scratch) n += s.pairs_total;
    return n;
}

// Cells into triangle order (parallel: each triangle fills its own range), in doubles
// for the walk and in floats padded to whole lanes for the force kernel.
void Relaxer::gather_by_triangle(const Cells &cells, size_t nt) {
    m_row.resize(nt + 1);
    m_padded_row.resize(nt + 1);
    m_row[0] = m_padded_row[0] = 0;
    for (TriId t = 0; t < nt; ++t) {
        const uint32_t n = static_cast<uint32_t>(cells.on(t).size());
        m_row[t + 1] = m_row[t] + n;
        m_padded_row[t + 1] =
            m_padded_row[t] + (n + force_lanes - 1) / force_lanes * force_lanes;
    }
    const size_t n = m_row[nt], padded = m_padded_row[nt];
    m_sx.resize(n);
    m_sz.resize(n);
    m_st.resize(n);
    m_sid.resize(n);
    m_fx.resize(padded);
    m_fz.resize(padded);
    m_ftype.resize(padded);
    m_chunk_x.resize(padded / force_lanes);
    m_chunk_z.resize(padded / force_lanes);
    m_chunk_radius.resize(padded / force_lanes);
    const double *xs = cells.x().data(), *zs = cells.z().data();
    const uint8_t *ts = cells.types().data();
    tbb::parallel_for(tbb::blocked_range<TriId>(0, static_cast<TriId>(nt), 256),
                      [&](const auto &range) {
                          for (TriId t = range.begin(); t != range.end(); ++t) {
                              uint32_t i = m_row[t], f = m_padded_row[t];
                              for (CellId c : cells.on(t)) {
                                  m_sx[i] = xs[c];
                                  m_sz[i] = zs[c];
                                  m_st[i] = ts[c];
                                  m_sid[i] = c;
                                  m_fx[f] = static_cast<float>(xs[c]);
                                  m_fz[f] = static_cast<float>(zs[c]);
                                  m_ftype[f] = ts[c];
                                  ++i;
                                  ++f;
                              }
                              for (; f < m_padded_row[t + 1]; ++f) {
                                  m_fx[f] = force_padding_position;
                                  m_fz[f] = 0;
                                  m_ftype[f] = 0;
                              }
                              bound_chunks(t);
                          }
                      });
}

// A circle about each chunk of t's cells (in t's frame), wide enough that floats
// rounded on the way into another frame stay inside it.
void Relaxer::bound_chunks(TriId t) {
    const double margin = 1e-5 * m_nbhd.bounding_radius(t);
    for (uint32_t first = m_row[t]; first < m_row[t + 1]; first += force_lanes) {
        const uint32_t last = std::min(first + force_lanes, m_row[t + 1]);
        double lo_x = m_sx[first], hi_x = lo_x, lo_z = m_sz[first], hi_z = lo_z;
        for (uint32_t p = first; p < last; ++p) {
            lo_x = std::min(lo_x, m_sx[p]);
            hi_x = std::max(hi_x, m_sx[p]);
            lo_z = std::min(lo_z, m_sz[p]);
            hi_z = std::max(hi_z, m_sz[p]);
        }
        const Vec2d centre{0.5 * (lo_x + hi_x), 0.5 * (lo_z + hi_z)};
        double radius = 0;
        for (uint32_t p = first; p < last; ++p)
            radius = std::max(radius, length(Vec2d{m_sx[p], m_sz[p]} - centre));
        const uint32_t c = (m_padded_row[t] + (first - m_row[t])) / force_lanes;
        m_chunk_x[c] = centre.x;
        m_chunk_z[c] = centre.y;
        m_chunk_radius[c] = static_cast<float>(radius * (1 + 1e-4) + margin);
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

// The pushes on the cells of triangle t, summed into D in t's frame: the chunks of every
// triangle of its unfolding are listed with their maps and circles in t's frame, and
// meet t's cells eight at a time (pair_forces.h).
void Relaxer::push_triangle(const RelaxContext &ctx, TriId t, const OneMinusAlpha &oma,
                            ForceScratch &s, Vec2d *D) const {
    const uint32_t begin = m_row[t], n = m_row[t + 1] - begin;
    const CellId *ids = m_sid.data() + begin;
    s.resize(n);
    for (uint32_t k = 0; k < n; ++k) {
        // Queiroz §V: a local w_r gives the moving cell its own radius.
        s.r[k] = ctx.cell_r ? ctx.cell_r[ids[k]] : ctx.r;
        s.target_r[k] = static_cast<float>(s.r[k]);
        s.target_x[k] = m_fx[m_padded_row[t] + k];
        s.target_z[k] = m_fz[m_padded_row[t] + k];
        const double *row = one_minus_alpha_row(ctx, oma, begin + k);
        for (int q = 0; q < max_cell_types; ++q)
            s.target_oma[size_t(k) * max_cell_types + q] = static_cast<float>(row[q]);
    }
    list_candidate_chunks(t, s);
    const ForceCandidates candidates{
        m_fx.data(),       m_fz.data(),       m_ftype.data(),  s.first.data(),
        s.map_c.data(),    s.map_s.data(),    s.map_x.data(),  s.map_z.data(),
        s.centre_x.data(), s.centre_z.data(), s.radius.data(), s.chunks};
    const ForceTargets targets{
        s.target_x.data(), s.target_z.data(), s.target_r.data(), s.target_oma.data(), n,
        m_padded_row[t]};
    add_pair_forces(
        targets, candidates,
        ForceSums{s.sum_x.data(), s.sum_z.data(), s.coincident.data(), s.pairs.data()});
    for (uint32_t k = 0; k < n; ++k) {
        s.pairs_total += s.pairs[k];
        D[k] = Vec2d{s.sum_x[k], s.sum_z[k]};
        if (s.coincident[k])
            D[k] += tie_break_pushes(ctx, oma, begin + k, s, candidates, targets, k);
    }
}

// The chunks of t's unfolding in entry order, with the map into t's frame in floats
// (its rounding, 1e-7 of the frame's size, is far below any distance the forces
// resolve) and their circles carried there, padded to whole lanes of chunks.
void Relaxer::list_candidate_chunks(TriId t, ForceScratch &s) const {
    const auto &entries = m_nbhd.of(t);
    size_t most = 0;
    for (const Neighbourhoods::Entry &e : entries)
        most += (m_padded_row[e.tri + 1] - m_padded_row[e.tri]) / force_lanes;
    s.room_for_chunks(most + force_lanes);
    uint32_t c = 0;
    for (const Neighbourhoods::Entry &e : entries) {
        const TriId j = e.tri;
        const RigidMap2 G = e.to_nbr.inverse();  // F[j→t]
        const float gc = static_cast<float>(G.c), gs = static_cast<float>(G.s),
                    gx = static_cast<float>(G.ax), gz = static_cast<float>(G.ay);
        for (uint32_t jc = m_padded_row[j] / force_lanes;
             jc < m_padded_row[j + 1] / force_lanes; ++jc, ++c) {
            const Vec2d centre = G.apply({m_chunk_x[jc], m_chunk_z[jc]});
            s.first[c] = jc * force_lanes;
            s.tri[c] = j;
            s.map_c[c] = gc;
            s.map_s[c] = gs;
            s.map_x[c] = gx;
            s.map_z[c] = gz;
            s.centre_x[c] = static_cast<float>(centre.x);
            s.centre_z[c] = static_cast<float>(centre.y);
            s.radius[c] = m_chunk_radius[jc];
        }
    }
    for (; c % force_lanes; ++c) {  // never reached: no kernel reads their cells
        s.first[c] = 0;
        s.tri[c] = t;
        s.map_c[c] = 1;
        s.map_s[c] = s.map_x[c] = s.map_z[c] = 0;
        s.centre_x[c] = s.centre_z[c] = force_padding_position;
        s.radius[c] = 0;
    }
    s.chunks = c;
}

// The pushes on target k from the candidates lying exactly on it (as the kernel's
// floats see them): each pair separates along its hashed direction, in t's frame.
Vec2d Relaxer::tie_break_pushes(const RelaxContext &ctx, const OneMinusAlpha &oma,
                                uint32_t row_k, const ForceScratch &s,
                                const ForceCandidates &candidates,
                                const ForceTargets &targets, uint32_t k) const {
    const double *row = one_minus_alpha_row(ctx, oma, row_k);
    const float qx = targets.x[k], qz = targets.z[k], r = targets.r[k];
    Vec2d push{};
    for (uint32_t c = 0; c < candidates.chunks; ++c) {
        if (!reaches_chunk(qx, qz, r, candidates, c)) continue;
        const TriId j = s.tri[c];
        for (uint32_t l = 0; l < force_lanes; ++l) {
            const uint32_t p = candidates.first[c] + l;
            const float px = m_fx[p], pz = m_fz[p];
            const float dx = qx - (s.map_c[c] * px - s.map_s[c] * pz + s.map_x[c]);
            const float dz = qz - (s.map_s[c] * px + s.map_c[c] * pz + s.map_z[c]);
            const float d2 = dx * dx + dz * dz;
            if (px == force_padding_position || p == targets.self + k || !(d2 < r * r) ||
                d2 != 0.0f)
                continue;
            const uint32_t row_p = m_row[j] + (p - m_padded_row[j]);
            const Vec2d u = tie_break_direction(ctx.seed, m_sid[row_k], m_sid[row_p]);
            push += u * (row[m_st[row_p]] * s.r[k]);
        }
    }
    return push;
}

// The row of 1 − α that the cell at row i feels from each type.
const double *Relaxer::one_minus_alpha_row(const RelaxContext &ctx,
                                           const OneMinusAlpha &oma, uint32_t i) const {
    return ctx.cell_one_minus_alpha && !ctx.uniform_alpha
               ? ctx.cell_one_minus_alpha + size_t(m_sid[i]) * max_cell_types
               : oma.m[m_st[i]];
}

// The displacement of every active cell (parallel over active triangles; each writes
// only its own cells).
void Relaxer::accumulate_forces(const RelaxContext &ctx,
                                const std::vector<TriId> &active) {
    const bool aniso = ctx.field && !ctx.field->empty() && ctx.w_a > 0;
    const double iso_weight = (1.0 - ctx.w_a) * ctx.w_d;
    // 1 − α for every pair, resolved once per step (the initial phase uses one α).
    OneMinusAlpha one_minus_alpha;
    for (int c = 0; c < max_cell_types; ++c)
        for (int q = 0; q < max_cell_types; ++q)
            one_minus_alpha.m[c][q] =
                ctx.uniform_alpha ? 1.0 - ctx.alpha
                                  : (c < ctx.types->size() && q < ctx.types->size()
                                         ? ctx.types->one_minus_alpha(c, q)
                                         : 0.0);

    // --- Forces (parallel over active triangles; each writes only its own cells) ---
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, active.size(), 8), [&](const auto &range) {
            ForceScratch &scratch = m_force_scratch.local();
            for (size_t ai = range.begin(); ai != range.end(); ++ai) {
                const TriId t = active[ai];
                const uint32_t mine_begin = m_row[t], mine_end = m_row[t + 1];
                if (mine_begin == mine_end) continue;
                Vec2d *D = m_move.data() + m_active_row[ai];
                push_triangle(ctx, t, one_minus_alpha, scratch, D);
                const CellId *ids = m_sid.data();
                // SG01 §3.2.1: C' = C + w_a·O + (1 − w_a)·w_d·D, O = (D·Â)·A
                for (uint32_t k = 0; k < mine_end - mine_begin; ++k) {
                    const CellId id = ids[mine_begin + k];
                    const double w_a = ctx.cell_w_a ? ctx.cell_w_a[id] : ctx.w_a;
                    const double w_d = ctx.cell_w_d ? ctx.cell_w_d[id] : ctx.w_d;
                    const bool local = ctx.cell_w_a || ctx.cell_w_d;
                    Vec2d m = D[k] * (local ? (1.0 - w_a) * w_d : iso_weight);
                    if (aniso) {
                        Vec2d A = ctx.field->a[t];
                        if (ctx.cell_a_scale) A = A * ctx.cell_a_scale[id];
                        const double a2 = length_squared(A);
                        if (a2 > 0)
                            m += A *
                                 (w_a * dot(D[k], A) / std::sqrt(a2));  // |O| = (D·Â)|A|
                    }
                    D[k] = m;
                }
            }
        });
}

template <typename Fn>
void Relaxer::for_each_neighbour(TriId t, uint32_t k, double r, Fn &&fn) const {
    const double r2 = r * r;
    const double *xs = m_sx.data(), *zs = m_sz.data();
    const Vec2d c{xs[k], zs[k]};
    for (const Neighbourhoods::Entry &e : m_nbhd.of(t)) {
        const uint32_t theirs_begin = m_row[e.tri], theirs_end = m_row[e.tri + 1];
        if (theirs_begin == theirs_end) continue;
        const RigidMap2 &F = e.to_nbr;
        const Vec2d q = F.apply(c);  // C in j's frame
        // A cell farther than r from j's bounding circle has no neighbour on j.
        const double reach = r + m_nbhd.bounding_radius(e.tri);
        if (q.x * q.x + q.y * q.y > reach * reach) continue;
        for (uint32_t p = theirs_begin; p < theirs_end; ++p) {
            const double dx = q.x - xs[p], dz = q.y - zs[p];
            const double d2 = dx * dx + dz * dz;
            if (d2 >= r2 || p == k) continue;
            // Back into t's frame: the rotation of F[j→t] is the inverse one.
            fn(p, Vec2d{F.c * dx + F.s * dz, -F.s * dx + F.c * dz}, d2);
        }
    }
}

std::vector<RelaxNeighbour> Relaxer::neighbours(const RelaxContext &ctx,
                                                const Cells &cells, CellId c) {
    m_nbhd.update(*ctx.crps, ctx.r);
    gather_by_triangle(cells, ctx.crps->num_triangles());
    const TriId t = cells.tri(c);
    std::vector<RelaxNeighbour> out;
    for (uint32_t k = m_row[t]; k < m_row[t + 1]; ++k) {
        if (m_sid[k] != c) continue;
        for_each_neighbour(t, k, ctx.r, [&](uint32_t p, Vec2d away, double d2) {
            out.push_back({m_sid[p], std::sqrt(d2), away});
        });
    }
    return out;
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
