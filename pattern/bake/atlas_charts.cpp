#include "pattern/bake/atlas_charts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <unordered_map>

namespace pelage::pattern::bake {
namespace {

using sim::TriId;
using sim::Vec2d;
using Tri2 = std::array<Vec2d, 3>;

// Whether two triangles' interiors overlap (separating axes: the six edge normals);
// `eps` lets triangles that share an edge or a vertex touch.
bool interiors_overlap(const Tri2 &a, const Tri2 &b, double eps) {
    for (const Tri2 *t : {&a, &b})
        for (int k = 0; k < 3; ++k) {
            const Vec2d e = (*t)[(k + 1) % 3] - (*t)[k], n{-e.y, e.x};
            const double len = length(n);
            if (len <= 0) continue;
            double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
            for (int c = 0; c < 3; ++c) {
                const double pa = dot(a[c], n) / len, pb = dot(b[c], n) / len;
                amin = std::min(amin, pa);
                amax = std::max(amax, pa);
                bmin = std::min(bmin, pb);
                bmax = std::max(bmax, pb);
            }
            if (amax <= bmin + eps || bmax <= amin + eps) return false;
        }
    return true;
}

}  // namespace

std::vector<Chart> grow_charts(const sim::Crps &crps, double max_angle_deg) {
    const size_t nt = crps.num_triangles();
    const sim::Topology &topo = crps.topology();
    double edge_sum = 0;
    for (TriId t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k)
            edge_sum += length(crps.frame(t).v[(k + 1) % 3] - crps.frame(t).v[k]);
    const double cell = std::max(edge_sum / std::max<size_t>(3 * nt, 1), 1e-300);
    const double eps = 1e-7 * cell, cos_max = std::cos(max_angle_deg * M_PI / 180);

    std::vector<TriId> seeds(nt);
    std::iota(seeds.begin(), seeds.end(), 0);
    std::stable_sort(seeds.begin(), seeds.end(), [&](TriId a, TriId b) {
        return crps.frame(a).area > crps.frame(b).area;
    });
    std::vector<uint8_t> assigned(nt, 0);
    std::vector<Chart> charts;
    std::unordered_map<int64_t, std::vector<uint32_t>> grid;
    auto key = [](int64_t x, int64_t y) { return (x << 32) ^ (y & 0xffffffff); };
    auto cells_of = [&](const Tri2 &p, auto fn) {
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
        for (const Vec2d &q : p) {
            x0 = std::min(x0, q.x);
            x1 = std::max(x1, q.x);
            y0 = std::min(y0, q.y);
            y1 = std::max(y1, q.y);
        }
        for (int64_t y = int64_t(std::floor(y0 / cell));
             y <= int64_t(std::floor(y1 / cell)); ++y)
            for (int64_t x = int64_t(std::floor(x0 / cell));
                 x <= int64_t(std::floor(x1 / cell)); ++x)
                fn(key(x, y));
    };

    for (TriId seed : seeds) {
        if (assigned[seed]) continue;
        Chart c;
        grid.clear();
        const sim::Vec3d n0 = crps.frame(seed).normal;
        auto add = [&](TriId t, const Tri2 &p) {
            assigned[t] = 1;
            const uint32_t local = uint32_t(c.tris.size());
            c.tris.push_back(t);
            c.pos.push_back(p);
            cells_of(p, [&](int64_t k) { grid[k].push_back(local); });
        };
        add(seed, crps.frame(seed).v);
        // Nearest candidates first (distance of their unfolded centroid from the seed's):
        // the chart grows as a disk, so its outline stays compact and packs well.
        const Vec2d origin = (c.pos[0][0] + c.pos[0][1] + c.pos[0][2]) / 3;
        struct Candidate {
            double d2;
            TriId tri;
            Tri2 p;
            bool operator<(const Candidate &o) const {
                return d2 > o.d2 || (d2 == o.d2 && tri > o.tri);  // min-heap
            }
        };
        std::priority_queue<Candidate> heap;
        auto offer = [&](size_t local) {
            const TriId t = c.tris[local];
            for (int k = 0; k < 3; ++k) {
                const TriId n = topo.across(t, k);
                if (n == sim::invalid_id || assigned[n]) continue;
                if (dot(crps.frame(n).normal, n0) < cos_max) continue;
                // n's corners on the shared edge, and its reference triangle moved
                // rigidly so that edge lands on the chart's copy of it.
                const sim::VertId A = crps.corners(t)[k],
                                  B = crps.corners(t)[(k + 1) % 3];
                int ia = -1, ib = -1;
                for (int q = 0; q < 3; ++q) {
                    if (crps.corners(n)[q] == A) ia = q;
                    if (crps.corners(n)[q] == B) ib = q;
                }
                if (ia < 0 || ib < 0) continue;
                const Tri2 &v = crps.frame(n).v;
                const Vec2d PA = c.pos[local][k], PB = c.pos[local][(k + 1) % 3];
                if (length(v[ib] - v[ia]) <= 0 || length(PB - PA) <= 0) continue;
                const sim::RigidMap2 m =
                    sim::RigidMap2::aligning(v[ib] - v[ia], PB - PA, v[ia], PA);
                const Tri2 p{m.apply(v[0]), m.apply(v[1]), m.apply(v[2])};
                heap.push({length_squared((p[0] + p[1] + p[2]) / 3 - origin), n, p});
            }
        };
        offer(0);
        while (!heap.empty()) {
            const Candidate cand = heap.top();
            heap.pop();
            if (assigned[cand.tri]) continue;
            bool overlap = false;
            cells_of(cand.p, [&](int64_t key_) {
                if (overlap) return;
                const auto it = grid.find(key_);
                if (it == grid.end()) return;
                for (uint32_t j : it->second)
                    if (interiors_overlap(cand.p, c.pos[j], eps)) {
                        overlap = true;
                        return;
                    }
            });
            if (overlap) continue;
            add(cand.tri, cand.p);
            offer(c.tris.size() - 1);
        }
        charts.push_back(std::move(c));
    }
    return charts;
}

void orient_chart(Chart &c) {
    std::vector<Vec2d> pts;
    for (const Tri2 &p : c.pos) pts.insert(pts.end(), p.begin(), p.end());
    std::sort(pts.begin(), pts.end(),
              [](Vec2d a, Vec2d b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    // Andrew's monotone chain.
    std::vector<Vec2d> hull(2 * pts.size());
    size_t k = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0) --k;
        hull[k++] = pts[i];
    }
    for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 1] - hull[k - 2], pts[i] - hull[k - 2]) <= 0)
            --k;
        hull[k++] = pts[i];
    }
    hull.resize(k > 1 ? k - 1 : k);
    double best = 1e300, bc = 1, bs = 0;
    for (size_t i = 0; i < hull.size(); ++i) {
        const Vec2d e = hull[(i + 1) % hull.size()] - hull[i];
        const double len = length(e);
        if (len <= 0) continue;
        const double co = e.x / len, si = -e.y / len;  // rotate e onto +x
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
        for (const Vec2d &p : hull) {
            const double x = co * p.x - si * p.y, y = si * p.x + co * p.y;
            x0 = std::min(x0, x);
            x1 = std::max(x1, x);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
        }
        if ((x1 - x0) * (y1 - y0) < best * (1 - 1e-9)) {
            best = (x1 - x0) * (y1 - y0);
            bc = co;
            bs = si;
            if (y1 - y0 > x1 - x0) {  // lie flat: a further quarter turn
                const double tc = bc;
                bc = -bs;
                bs = tc;
            }
        }
    }
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (Tri2 &p : c.pos)
        for (Vec2d &q : p) {
            q = {bc * q.x - bs * q.y, bs * q.x + bc * q.y};
            x0 = std::min(x0, q.x);
            x1 = std::max(x1, q.x);
            y0 = std::min(y0, q.y);
            y1 = std::max(y1, q.y);
        }
    for (Tri2 &p : c.pos)
        for (Vec2d &q : p) q = q - Vec2d{x0, y0};
    c.w = x1 - x0;
    c.h = y1 - y0;
    c.area = 0;
    for (const Tri2 &p : c.pos) c.area += 0.5 * std::abs(cross(p[1] - p[0], p[2] - p[0]));
}

}  // namespace pelage::pattern::bake
