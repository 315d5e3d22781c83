#include "sim/mosaic/neighbourhoods.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "sim/crps/unfold.h"
#include "sim/geodesic/geodesic_mesh.h"
#include "sim/geodesic/window_propagation.h"

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

}  // namespace pelage::sim
