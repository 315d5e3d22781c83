#include "sim/mosaic/relaxation.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "sim/core/random.h"
#include "sim/crps/unfold.h"
#include "sim/geodesic/geodesic_mesh.h"
#include "sim/geodesic/window_propagation.h"
#include "sim/mosaic/pair_forces.h"

namespace pelage::sim {

size_t Neighbourhoods::entries() const {
    size_t n = 0;
    for (const auto &e : m_entries) n += e.size();
    return n;
}

size_t Neighbourhoods::bytes() const {
    return entries() * sizeof(Entry) + m_entries.size() * sizeof(m_entries[0]) +
           m_bounding.size() * sizeof(double);
}

namespace {

// An image of a triangle in the unfolding about a master triangle t.
struct Image {
    TriId tri;
    uint32_t next;  // the next image of the same triangle in the queue, or none
    RigidMap2 to_t;
};
constexpr uint32_t none = ~uint32_t(0);

// One thread's working lists, kept across the triangles it unfolds.
struct UnfoldingScratch {
    UnfoldScratch visited;
    std::vector<uint32_t> first;  // valid where visited: tri → first image's index
    std::vector<Image> queue;
    std::optional<WindowPropagation> propagation;
    std::vector<GeodesicWindow> windows;
    std::vector<TriId> tris;
};

// The neighbourhood of one triangle at a time: what every triangle's unfolding reads
// (the surface, the radius, the tolerance) is fixed here, the rest is the thread's.
class Unfolder {
  public:
    Unfolder(const Crps &crps, const double *bounding, double R, bool verified)
        : crps(crps),
          topo(crps.topology()),
          bounding(bounding),
          R(R),
          tolerance(Neighbourhoods::image_tolerance * R),
          verified(verified) {}

    // t's entries, in triangle order, into out.
    void neighbourhood(TriId t, UnfoldingScratch &s,
                       std::vector<Neighbourhoods::Entry> &out) const {
        const bool consistent = unfold(t, s);
        collect_reached(s);
        out.reserve(s.tris.size());
        if (!verified || consistent) {
            for (TriId j : s.tris) {
                const RigidMap2 &to_t = s.queue[s.first[j]].to_t;
                out.push_back({j, float(unfolded_distance(t, j, to_t)), to_t.inverse()});
            }
            return;
        }
        keep_geodesically_checked_images(t, s, out);
    }

  private:
    // Whether two unfoldings put j in the same place, within the tolerance: a shift of
    // its centroid plus a turn times its bounding radius.
    bool same_place(const RigidMap2 &F, const RigidMap2 &G, TriId j) const {
        const double dx = F.ax - G.ax, dy = F.ay - G.ay;
        const double turn = std::abs(F.s * G.c - F.c * G.s) * bounding[j];
        return dx * dx + dy * dy <= 0.25 * tolerance * tolerance &&
               turn <= 0.5 * tolerance;
    }

    // Breadth-first unfolding across edges (fewest hops, then neighbour order) into
    // s.queue. Returns whether every path to every triangle unfolds it to one place and
    // no edge within reach is a boundary: then the unfolding is the surface laid flat
    // without overlaps or gaps, and a straight segment in it is a path on the surface.
    bool unfold(TriId t, UnfoldingScratch &s) const {
        s.visited.begin();
        s.visited.visit(t);
        s.queue.clear();
        s.queue.push_back({t, none, RigidMap2{}});
        s.first[t] = 0;
        const Vec2d *vt = crps.frame(t).v.data();
        bool consistent = true;
        for (size_t head = 0; head < s.queue.size(); ++head) {
            const Image parent = s.queue[head];
            consistent = consistent && topo.num_primary[parent.tri] == 3;
            // Other images are not walked on from: the paths on either side of a vertex
            // meet at its far side, where one step from each side's first images gives
            // both places.
            if (s.first[parent.tri] != head) continue;
            const auto nbrs = topo.neighbours(parent.tri);
            const auto maps = crps.to_master(parent.tri);
            for (size_t k = 0; k < topo.num_primary[parent.tri]; ++k) {
                const RigidMap2 F = compose(parent.to_t, maps[k]);
                step_onto(t, vt, nbrs[k], F, s, consistent);
            }
        }
        return consistent;
    }

    // One step of the unfolding onto j, which F carries into t's frame: j gets an image
    // there unless one of its images is there already or it is out of reach.
    void step_onto(TriId t, const Vec2d *vt, TriId j, const RigidMap2 &F,
                   UnfoldingScratch &s, bool &consistent) const {
        if (j == t) {  // around a cylinder or a cone back to t
            consistent = consistent && same_place(F, RigidMap2{}, j);
            return;
        }
        const bool first_time = s.visited.visit(j);
        uint32_t last = none;
        int images = 0;
        if (!first_time) {
            if (!verified) return;  // first path wins
            if (has_image_at(F, j, s, images, last)) return;
        }
        if (!within_reach(t, vt, j, F)) {
            if (first_time) s.visited.unvisit(j);  // another path may be nearer
            return;
        }
        if (first_time) {
            s.first[j] = static_cast<uint32_t>(s.queue.size());
        } else {
            // Two paths unfold j to different places within R.
            consistent = false;
            if (images >= Neighbourhoods::max_images) return;
            s.queue[last].next = static_cast<uint32_t>(s.queue.size());
        }
        s.queue.push_back({j, none, F});
    }

    // Whether one of j's images is where F puts it; the images tried are counted in
    // images, the last of them left in last.
    bool has_image_at(const RigidMap2 &F, TriId j, const UnfoldingScratch &s, int &images,
                      uint32_t &last) const {
        bool same = false;
        for (uint32_t i = s.first[j]; i != none && !same; i = s.queue[i].next) {
            same = same_place(F, s.queue[i].to_t, j);
            ++images;
            last = i;
        }
        return same;
    }

    // Whether j, carried by F, comes within R of t, with cheap tests first: the
    // centroid (origin of every 2D frame) of j mapped into t's frame within R accepts;
    // farther than R plus both bounding radii rejects; only the cases in between pay
    // for the exact triangle–triangle distance.
    bool within_reach(TriId t, const Vec2d *vt, TriId j, const RigidMap2 &F) const {
        const double dc = std::hypot(F.ax, F.ay);  // F applied to j's centroid
        bool accept = dc <= R;
        if (!accept && dc <= R + bounding[t] + bounding[j]) {
            const auto &vj = crps.frame(j).v;
            const Vec2d mapped[3] = {F.apply(vj[0]), F.apply(vj[1]), F.apply(vj[2])};
            accept = triangle_triangle_distance(vt, mapped) <= R;
        }
        return accept;
    }

    // How far j, carried into t's frame by to_t, lies from t in the unfolding.
    double unfolded_distance(TriId t, TriId j, const RigidMap2 &to_t) const {
        if (j == t) return 0;
        const auto &vt = crps.frame(t).v, &vj = crps.frame(j).v;
        const Vec2d mapped[3] = {to_t.apply(vj[0]), to_t.apply(vj[1]), to_t.apply(vj[2])};
        return triangle_triangle_distance(vt.data(), mapped);
    }

    // The triangles reached, in triangle order (the force loop's order), into s.tris.
    static void collect_reached(UnfoldingScratch &s) {
        s.tris.clear();
        for (const Image &im : s.queue)
            if (s.first[im.tri] == uint32_t(&im - s.queue.data()))
                s.tris.push_back(im.tri);
        std::sort(s.tris.begin(), s.tris.end());
    }

    // Each reached triangle's image that agrees best with the exact distances from t's
    // centroid, if it agrees within the tolerance. Every point within R of t lies
    // within R + t's bounding radius of the centroid.
    void keep_geodesically_checked_images(TriId t, UnfoldingScratch &s,
                                          std::vector<Neighbourhoods::Entry> &out) const {
        s.propagation->run(t, Vec2d{0, 0}, R + bounding[t] + 1e-9 * R, s.windows);
        std::stable_sort(s.windows.begin(), s.windows.end(),
                         [](const GeodesicWindow &a, const GeodesicWindow &b) {
                             return a.face < b.face;
                         });
        for (TriId j : s.tris) {
            const auto lo = std::lower_bound(
                s.windows.begin(), s.windows.end(), j,
                [](const GeodesicWindow &w, TriId f) { return w.face < f; });
            auto hi = lo;
            while (hi != s.windows.end() && hi->face == j) ++hi;
            uint32_t best = none;
            double best_error = std::numeric_limits<double>::infinity();
            if (j == t) {
                best = 0;
                best_error = 0;
            } else if (lo != hi) {
                best = best_image(j, &*lo, &*lo + (hi - lo), s, best_error);
            }
            if (best == none || best_error > tolerance) continue;
            const RigidMap2 &to_t = s.queue[best].to_t;
            // Kept for a radius R' while its error is within image_tolerance·R'.
            const double needs = std::max(unfolded_distance(t, j, to_t),
                                          best_error / Neighbourhoods::image_tolerance);
            out.push_back({j, float(needs), to_t.inverse()});
        }
    }

    // The image of j whose distances from t's centroid, at j's corners, edge midpoints
    // and centroid, differ least from the exact ones the windows over j give (none if
    // no sample has one); its largest difference into best_error.
    uint32_t best_image(TriId j, const GeodesicWindow *windows_begin,
                        const GeodesicWindow *windows_end, const UnfoldingScratch &s,
                        double &best_error) const {
        const auto &v = crps.frame(j).v;
        const Vec2d samples[7] = {{0, 0},
                                  v[0],
                                  v[1],
                                  v[2],
                                  (v[0] + v[1]) * 0.5,
                                  (v[1] + v[2]) * 0.5,
                                  (v[2] + v[0]) * 0.5};
        uint32_t best = none;
        for (uint32_t i = s.first[j]; i != none; i = s.queue[i].next) {
            const RigidMap2 &F = s.queue[i].to_t;
            double error = 0;
            int known = 0;
            for (const Vec2d &q : samples) {
                const double exact = distance_from_windows(windows_begin, windows_end, q);
                if (!std::isfinite(exact)) continue;
                error = std::max(error, std::abs(length(F.apply(q)) - exact));
                ++known;
            }
            if (known > 0 && error < best_error) {
                best_error = error;
                best = i;
            }
        }
        return best;
    }

    const Crps &crps;
    const Topology &topo;
    const double *bounding;  // per triangle, the bounding radius about its centroid
    const double R, tolerance;
    const bool verified;
};

}  // namespace

void Neighbourhoods::update(const Crps &crps, double r) {
    const size_t nt = crps.num_triangles();
    const bool built = m_entries.size() == nt && m_radius > 0 && r <= m_radius;
    if (built && r * slack * filter_ratio >= m_radius) return;
    const auto start = std::chrono::steady_clock::now();
    if (built) {
        filter(r * slack);
        m_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
        return;
    }
    m_radius = r * slack;
    m_entries.assign(nt, {});
    m_bounding.resize(nt);
    for (TriId t = 0; t < nt; ++t) {
        const auto &v = crps.frame(t).v;
        m_bounding[t] = std::max({length(v[0]), length(v[1]), length(v[2])});
    }
    ++m_rebuilds;
    std::optional<GeodesicMesh> geodesic_mesh;
    // Saddles flatter than half the tolerance bend no path: they change a distance by
    // at most that angle times the distance (geodesic_mesh.h), and skipping them saves
    // most pseudo-sources on noisy meshes.
    if (m_verified)
        geodesic_mesh.emplace(crps, GeodesicMeshOptions{0.5 * image_tolerance});

    tbb::enumerable_thread_specific<UnfoldingScratch> scratch;
    const Unfolder unfolder(crps, m_bounding.data(), m_radius, m_verified);
    tbb::parallel_for(tbb::blocked_range<TriId>(0, static_cast<TriId>(nt), 64),
                      [&](const auto &range) {
                          UnfoldingScratch &s = scratch.local();
                          s.visited.prepare(nt);
                          s.first.resize(nt);
                          if (m_verified && !s.propagation)
                              s.propagation.emplace(*geodesic_mesh);
                          for (TriId t = range.begin(); t != range.end(); ++t)
                              unfolder.neighbourhood(t, s, m_entries[t]);
                      });
    m_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The entries of a smaller radius R from those of a larger one: a triangle stays while
// it lies within R in its unfolding and its image agrees with the exact geodesics within
// image_tolerance·R. Every triangle of a fresh build at R is among them, but for one
// reached only by a path that the larger radius's unfolding did not keep (max_images);
// a triangle that is kept may have been left unchecked by a fresh build (its unfolding
// agreeing with itself) and now be dropped: the subset errs on the side of no fold.
void Neighbourhoods::filter(double R) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, m_entries.size(), 256), [&](const auto &range) {
            for (size_t t = range.begin(); t != range.end(); ++t) {
                auto &e = m_entries[t];
                e.erase(
                    std::remove_if(e.begin(), e.end(),
                                   [R](const Entry &x) { return double(x.needs) > R; }),
                    e.end());
            }
        });
    m_radius = R;
    ++m_filters;
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
                                  m_fx[f] = m_fz[f] = force_padding_position;
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

// The pushes on the cells of triangle t, summed into D in t's frame: the cells of every
// triangle of its unfolding, with their chunks' circles, are carried into t's frame
// once, and meet t's cells eight at a time (pair_forces.h).
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
    const uint32_t self = gather_candidates(t, s);
    const ForceCandidates candidates{s.x.data(),
                                     s.z.data(),
                                     s.type.data(),
                                     s.centre_x.data(),
                                     s.centre_z.data(),
                                     s.radius.data(),
                                     static_cast<uint32_t>(s.radius.size())};
    const ForceTargets targets{s.target_x.data(),
                               s.target_z.data(),
                               s.target_r.data(),
                               s.target_oma.data(),
                               n,
                               self};
    add_pair_forces(
        targets, candidates,
        ForceSums{s.sum_x.data(), s.sum_z.data(), s.coincident.data(), s.pairs.data()});
    for (uint32_t k = 0; k < n; ++k) {
        s.pairs_total += s.pairs[k];
        D[k] = Vec2d{s.sum_x[k], s.sum_z[k]};
        if (s.coincident[k]) D[k] += tie_break_pushes(ctx, oma, begin + k, s, targets, k);
    }
}

// The cells of t's unfolding carried into t's frame, in entry order, each triangle's
// padded to whole chunks and the chunks to whole lanes. Returns where t's own cells
// start.
uint32_t Relaxer::gather_candidates(TriId t, ForceScratch &s) const {
    const auto &entries = m_nbhd.of(t);
    uint32_t chunks = 0;
    for (const Neighbourhoods::Entry &e : entries)
        chunks += (m_padded_row[e.tri + 1] - m_padded_row[e.tri]) / force_lanes;
    const uint32_t lanes_of_chunks =
        (chunks + force_lanes - 1) / force_lanes * force_lanes;
    s.resize_candidates(lanes_of_chunks);
    float *x = s.x.data(), *z = s.z.data();
    int32_t *type = s.type.data();
    uint32_t *row = s.row.data();
    uint32_t c = 0, self = 0;
    for (const Neighbourhoods::Entry &e : entries) {
        const TriId j = e.tri;
        const uint32_t first = m_padded_row[j], padded = m_padded_row[j + 1] - first;
        if (padded == 0) continue;
        if (j == t) self = c * force_lanes;
        const RigidMap2 G = e.to_nbr.inverse();  // F[j→t]
        for (uint32_t jc = first / force_lanes; jc < (first + padded) / force_lanes;
             ++jc, ++c) {
            const Vec2d centre = G.apply({m_chunk_x[jc], m_chunk_z[jc]});
            s.centre_x[c] = static_cast<float>(centre.x);
            s.centre_z[c] = static_cast<float>(centre.y);
            s.radius[c] = m_chunk_radius[jc];
        }
        // The map in floats: its rounding (1e-7 of the frame's size) is far below any
        // distance the forces resolve.
        const float gc = static_cast<float>(G.c), gs = static_cast<float>(G.s),
                    gx = static_cast<float>(G.ax), gz = static_cast<float>(G.ay);
        const float *px = m_fx.data() + first, *pz = m_fz.data() + first;
        for (uint32_t p = 0; p < padded; ++p) {
            x[p] = gc * px[p] - gs * pz[p] + gx;
            z[p] = gs * px[p] + gc * pz[p] + gz;
        }
        const uint32_t n = m_row[j + 1] - m_row[j];
        for (uint32_t p = 0; p < n; ++p) row[p] = m_row[j] + p;
        std::copy_n(m_ftype.data() + first, padded, type);
        for (uint32_t p = n; p < padded; ++p) {
            x[p] = z[p] = force_padding_position;
            row[p] = ~uint32_t(0);
        }
        x += padded;
        z += padded;
        type += padded;
        row += padded;
    }
    s.cells = c * force_lanes;
    for (; c < lanes_of_chunks; ++c) {
        s.centre_x[c] = s.centre_z[c] = force_padding_position;
        s.radius[c] = 0;
    }
    return self;
}

// The pushes on target k from the candidates lying exactly on it (as the kernel's
// floats see them): each pair separates along its hashed direction, in t's frame.
Vec2d Relaxer::tie_break_pushes(const RelaxContext &ctx, const OneMinusAlpha &oma,
                                uint32_t row_k, const ForceScratch &s,
                                const ForceTargets &targets, uint32_t k) const {
    const double *row = one_minus_alpha_row(ctx, oma, row_k);
    const float qx = targets.x[k], qz = targets.z[k], r = targets.r[k];
    Vec2d push{};
    for (size_t p = 0; p < s.cells; ++p) {
        if (s.row[p] == ~uint32_t(0)) continue;
        const float dx = qx - s.x[p], dz = qz - s.z[p];
        const float d2 = dx * dx + dz * dz;
        if (!(d2 < r * r) || d2 != 0.0f || p == targets.self + k) continue;
        const Vec2d u = tie_break_direction(ctx.seed, m_sid[row_k], m_sid[s.row[p]]);
        push += u * (row[m_st[s.row[p]]] * s.r[k]);
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
