#include "sim/relaxation.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "sim/random.h"
#include "sim/unfold.h"

namespace pelage::sim {

void Neighbourhoods::update(const Crps &crps, double r) {
    const size_t nt = crps.num_triangles();
    if (m_entries.size() == nt && r <= m_radius && r * rebuild_ratio >= m_radius) return;
    m_radius = r * slack;
    m_entries.assign(nt, {});
    ++m_rebuilds;
    struct Scratch {
        UnfoldScratch unfold;
        std::vector<UnfoldedTriangle> out;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    const double R = m_radius;
    tbb::parallel_for(tbb::blocked_range<TriId>(0, static_cast<TriId>(nt), 64), [&](const auto &range) {
        Scratch &s = scratch.local();
        for (TriId t = range.begin(); t != range.end(); ++t) {
            unfold_around_triangle(crps, t, R, s.out, s.unfold);
            auto &e = m_entries[t];
            e.reserve(s.out.size());
            for (const UnfoldedTriangle &u : s.out) e.push_back({u.tri, u.to_master.inverse()});
        }
    });
}

namespace {

// Deterministic direction for two coincident cells (d = 0): a hashed angle of the pair,
// opposite for the two members so they separate (style.md §2.4: ties break on ids).
Vec2d tie_break_direction(uint64_t seed, CellId c, CellId p) {
    const CellId lo = std::min(c, p), hi = std::max(c, p);
    const uint64_t h = hash_counters(seed, static_cast<uint64_t>(RandomStream::tie_break),
                                     (uint64_t(lo) << 32) | hi);
    const double angle = double(h >> 11) * 0x1.0p-53 * 6.283185307179586;
    const Vec2d d{std::cos(angle), std::sin(angle)};
    return c == lo ? d : d * -1.0;
}

}  // namespace

RelaxStepResult Relaxer::step(const RelaxContext &ctx, Cells &cells, const std::vector<TriId> &active) {
    const Crps &crps = *ctx.crps;
    m_nbhd.update(crps, ctx.r);

    // --- Offsets of each active triangle's cells in the move buffer ---
    m_active_row.resize(active.size() + 1);
    m_active_row[0] = 0;
    for (size_t i = 0; i < active.size(); ++i)
        m_active_row[i + 1] = m_active_row[i] + static_cast<uint32_t>(cells.on(active[i]).size());
    const size_t n_active_cells = m_active_row.back();
    m_move.assign(n_active_cells, Vec2d{});
    m_dest.resize(n_active_cells);

    const double r = ctx.r, r2 = r * r, inv_r = 1.0 / r;
    const double *xs = cells.x().data(), *zs = cells.z().data();
    const uint8_t *ts = cells.types().data();
    const bool aniso = ctx.field && !ctx.field->empty() && ctx.w_a > 0;
    const double iso_weight = (1.0 - ctx.w_a) * ctx.w_d;

    // --- Forces (parallel over active triangles; each writes only its own cells) ---
    tbb::parallel_for(tbb::blocked_range<size_t>(0, active.size(), 8), [&](const auto &range) {
        for (size_t ai = range.begin(); ai != range.end(); ++ai) {
            const TriId t = active[ai];
            const auto &mine = cells.on(t);
            if (mine.empty()) continue;
            Vec2d *D = m_move.data() + m_active_row[ai];
            for (const Neighbourhoods::Entry &e : m_nbhd.of(t)) {
                const auto &theirs = cells.on(e.tri);
                if (theirs.empty()) continue;
                const RigidMap2 &F = e.to_nbr;
                for (size_t k = 0; k < mine.size(); ++k) {
                    const CellId c = mine[k];
                    const Vec2d q = F.apply({xs[c], zs[c]});  // C in j's frame
                    const uint8_t tc = ts[c];
                    double sx = 0, sz = 0;
                    for (const CellId p : theirs) {
                        const double dx = q.x - xs[p], dz = q.y - zs[p];
                        const double d2 = dx * dx + dz * dz;
                        if (d2 >= r2 || p == c) continue;
                        // Walter 1998 Fig. 1 step 1: f = 1 − d/r, D = unit(C − P)·f·(1 − α)·r
                        const double oma = ctx.uniform_alpha ? 1.0 - ctx.alpha
                                                             : ctx.types->one_minus_alpha(tc, ts[p]);
                        if (d2 > 0) {
                            const double d = std::sqrt(d2);
                            const double s = (1.0 - d * inv_r) * oma * r / d;
                            sx += dx * s;
                            sz += dz * s;
                        } else {
                            const Vec2d u = tie_break_direction(ctx.seed, c, p);
                            sx += u.x * oma * r;
                            sz += u.y * oma * r;
                        }
                    }
                    // Back into t's frame: the rotation of F[j→t] is the inverse one.
                    D[k].x += F.c * sx + F.s * sz;
                    D[k].y += -F.s * sx + F.c * sz;
                }
            }
            // SG01 §3.2.1: C' = C + w_a·O + (1 − w_a)·w_d·D, O = (D·Â)·A
            for (size_t k = 0; k < mine.size(); ++k) {
                Vec2d m = D[k] * iso_weight;
                if (aniso) {
                    const Vec2d A = ctx.field->a[t];
                    const double a2 = length_squared(A);
                    if (a2 > 0) m += A * (ctx.w_a * dot(D[k], A) / std::sqrt(a2));  // |O| = (D·Â)|A|
                }
                D[k] = m;
            }
        }
    });

    // --- Walk every moving cell across the surface (parallel, independent) ---
    tbb::parallel_for(tbb::blocked_range<size_t>(0, active.size(), 8), [&](const auto &range) {
        for (size_t ai = range.begin(); ai != range.end(); ++ai) {
            const auto &mine = cells.on(active[ai]);
            for (size_t k = 0; k < mine.size(); ++k) {
                const size_t i = m_active_row[ai] + k;
                const CellId c = mine[k];
                m_dest[i] = walk(crps, {active[ai], {xs[c], zs[c]}}, m_move[i]);
            }
        }
    });

    // --- Apply serially in triangle order: bucket edits stay deterministic ---
    RelaxStepResult result;
    result.cells_moved = n_active_cells;
    std::vector<CellId> ids;
    ids.reserve(n_active_cells);
    for (size_t ai = 0; ai < active.size(); ++ai)
        for (CellId c : cells.on(active[ai])) ids.push_back(c);
    for (size_t i = 0; i < n_active_cells; ++i) {
        result.max_move = std::max(result.max_move, length(m_move[i]));
        cells.move(ids[i], m_dest[i]);
    }
    return result;
}

}  // namespace pelage::sim
