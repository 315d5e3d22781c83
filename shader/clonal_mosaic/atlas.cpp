#include "shader/clonal_mosaic/atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace pelage::shader::clonal_mosaic {
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

struct Chart {
    std::vector<TriId> tris;
    std::vector<Tri2> pos;  // unfolded, then turned to the least-area box, min at 0
    double w = 0, h = 0, area = 0;
};

// Grows every chart (breadth-first from the largest unassigned triangle).
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

// Turns a chart to its least-area bounding box (one side along a convex-hull edge,
// Freeman & Shapira 1975), lying flat (w >= h), with its box's corner at the origin.
void orient(Chart &c) {
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

// The distance from q to triangle p (0 inside).
double distance_to_triangle(Vec2d q, const Tri2 &p) {
    const double s0 = cross(p[1] - p[0], q - p[0]), s1 = cross(p[2] - p[1], q - p[1]),
                 s2 = cross(p[0] - p[2], q - p[2]);
    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return 0;
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
        const Vec2d a = p[k], ab = p[(k + 1) % 3] - a;
        const double t =
            std::clamp(dot(q - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
        best = std::min(best, length(q - (a + ab * t)));
    }
    return best;
}

// A chart rasterised on the packing grid at one scale and orientation: per row of
// cells, the runs of cells within `margin` texels of its triangles.
struct Mask {
    struct Run {
        int32_t x, len;
    };
    int cols = 0, rows = 0;
    std::vector<std::vector<Run>> row_runs;
};

// Chart point p (chart units) in the mask's texel coordinates.
Vec2d mask_point(const Chart &c, Vec2d p, bool quarter_turn, double scale, double pad) {
    const Vec2d q = quarter_turn ? Vec2d{c.h - p.y, p.x} : p;
    return q * scale + Vec2d{pad, pad};
}

Mask mask_of(const Chart &c, bool quarter_turn, double scale, double margin, double cs) {
    const double pad = margin + cs;
    const double w = (quarter_turn ? c.h : c.w) * scale + 2 * pad,
                 h = (quarter_turn ? c.w : c.h) * scale + 2 * pad;
    Mask m;
    m.cols = std::max(1, int(std::ceil(w / cs)));
    m.rows = std::max(1, int(std::ceil(h / cs)));
    std::vector<uint8_t> on(size_t(m.cols) * m.rows, 0);
    // A cell is taken when any of its points lies within the margin of a triangle.
    const double reach = margin + cs * M_SQRT1_2;
    for (const Tri2 &t : c.pos) {
        Tri2 q;
        double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
        for (int k = 0; k < 3; ++k) {
            q[k] = mask_point(c, t[k], quarter_turn, scale, pad);
            x0 = std::min(x0, q[k].x);
            x1 = std::max(x1, q[k].x);
            y0 = std::min(y0, q[k].y);
            y1 = std::max(y1, q[k].y);
        }
        const int cx0 = std::max(0, int(std::floor((x0 - reach) / cs))),
                  cx1 = std::min(m.cols - 1, int(std::floor((x1 + reach) / cs))),
                  cy0 = std::max(0, int(std::floor((y0 - reach) / cs))),
                  cy1 = std::min(m.rows - 1, int(std::floor((y1 + reach) / cs)));
        for (int y = cy0; y <= cy1; ++y)
            for (int x = cx0; x <= cx1; ++x) {
                uint8_t &cell = on[size_t(y) * m.cols + x];
                if (!cell &&
                    distance_to_triangle({(x + 0.5) * cs, (y + 0.5) * cs}, q) <= reach)
                    cell = 1;
            }
    }
    m.row_runs.resize(size_t(m.rows));
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols;) {
            if (!on[size_t(y) * m.cols + x]) {
                ++x;
                continue;
            }
            int e = x;
            while (e < m.cols && on[size_t(y) * m.cols + e]) ++e;
            m.row_runs[size_t(y)].push_back({x, e - x});
            x = e;
        }
    return m;
}

// The packing grid: per cell, the length of the run of free (or taken) cells starting
// there along its row, so a search skips whole runs at a time.
class Occupancy {
  public:
    Occupancy(int cols, int rows)
        : m_cols(cols),
          m_rows(rows),
          m_free(size_t(cols) * rows),
          m_taken(m_free.size()),
          m_longest(size_t(rows)) {
        for (int y = 0; y < rows; ++y) update_row(y);
    }
    // The first position (least row, then column) where m fits, in rows below
    // `row_limit`; false when none does.
    bool find(const Mask &m, int row_limit, int *px, int *py) const {
        // The mask's longest run: a row without as long a free run cannot take it.
        int widest_row = 0, widest = 0;
        for (int r = 0; r < m.rows; ++r)
            for (const Mask::Run &run : m.row_runs[size_t(r)])
                if (run.len > widest) {
                    widest = run.len;
                    widest_row = r;
                }
        for (int y = 0; y + m.rows <= m_rows && y < row_limit; ++y) {
            if (m_longest[size_t(y + widest_row)] < widest) continue;
            for (int x = 0; x + m.cols <= m_cols;) {
                int skip = 0;
                // The widest row first: it rejects most positions.
                for (int k = -1; k < m.rows && !skip; ++k) {
                    const int r = k < 0 ? widest_row : k;
                    if (k == widest_row) continue;
                    for (const Mask::Run &run : m.row_runs[size_t(r)]) {
                        const size_t i = size_t(y + r) * m_cols + x + run.x;
                        if (m_taken[i] > 0) {
                            skip = m_taken[i];
                            break;
                        }
                        if (m_free[i] < run.len) {
                            skip = m_free[i] + 1;
                            break;
                        }
                    }
                }
                if (!skip) {
                    *px = x;
                    *py = y;
                    return true;
                }
                x += skip;
            }
        }
        return false;
    }
    void place(const Mask &m, int px, int py) {
        for (int r = 0; r < m.rows; ++r) {
            if (m.row_runs[size_t(r)].empty()) continue;
            for (const Mask::Run &run : m.row_runs[size_t(r)])
                for (int k = 0; k < run.len; ++k)
                    m_taken[size_t(py + r) * m_cols + px + run.x + k] = 1;
            update_row(py + r);
        }
    }

  private:
    void update_row(int y) {
        int32_t *f = &m_free[size_t(y) * m_cols], *t = &m_taken[size_t(y) * m_cols];
        int32_t nf = 0, nt = 0, longest = 0;
        for (int x = m_cols - 1; x >= 0; --x) {
            const bool taken = t[x] > 0;
            nf = taken ? 0 : nf + 1;
            nt = taken ? nt + 1 : 0;
            f[x] = nf;
            t[x] = nt;
            longest = std::max(longest, nf);
        }
        m_longest[size_t(y)] = longest;
    }
    int m_cols, m_rows;
    std::vector<int32_t> m_free, m_taken;
    std::vector<int32_t> m_longest;  // per row, its longest free run
};

struct Placement {
    int x = 0, y = 0;
    bool quarter_turn = false;
};

// Places every chart, largest first, at the first position where it fits in either
// orientation; false when one fits nowhere.
bool bitmap_pack(const std::vector<Chart> &charts, const std::vector<size_t> &order,
                 double scale, double margin, double cs, int cols, int rows,
                 std::vector<Placement> *out) {
    Occupancy occ(cols, rows);
    out->assign(charts.size(), {});
    for (size_t i : order) {
        // Both orientations; the lower (then lefter) position wins, so the second
        // search stops at the first one's row.
        Mask m[2];
        int x[2] = {0, 0},
            y[2] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
        for (int turn = 0; turn < 2; ++turn) {
            m[turn] = mask_of(charts[i], turn == 1, scale, margin, cs);
            if (!occ.find(m[turn], turn ? y[0] : std::numeric_limits<int>::max(),
                          &x[turn], &y[turn]))
                y[turn] = std::numeric_limits<int>::max();
        }
        const int turn = y[1] < y[0] ? 1 : 0;
        const int best_x = x[turn], best_y = y[turn];
        const bool best_turn = turn == 1;
        Mask &best = m[turn];
        if (best_y == std::numeric_limits<int>::max()) return false;
        occ.place(best, best_x, best_y);
        (*out)[i] = {best_x, best_y, best_turn};
    }
    return true;
}

}  // namespace

double Atlas::coverage() const {
    double area = 0;
    for (const auto &p : corners) area += 0.5 * std::abs(cross(p[1] - p[0], p[2] - p[0]));
    return area / (double(width) * height);
}

Atlas pack_atlas(const sim::Crps &crps, int width, int height,
                 const AtlasOptions &options) {
    std::vector<Chart> charts = grow_charts(crps, options.max_chart_angle_deg);
    double area = 0;
    for (Chart &c : charts) {
        orient(c);
        area += c.area;
    }
    std::vector<size_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return charts[a].area > charts[b].area; });
    // A packing grid of at most 2048 cells a side: at most two texels per cell.
    const double cs = std::max(1.0, std::ceil(double(std::max(width, height)) / 2048));
    const int cols = int(width / cs), rows = int(height / cs);
    // Charts keep `gutter` texels between them: half a gutter each.
    const double margin = 0.5 * options.gutter;

    // The scale: bisection on a grid four times coarser (sixteen times fewer cells),
    // whose masks are more conservative, then a few steps up on the fine grid. No
    // packing reaches 90 % with gutters: the bisection starts below that.
    const double coarse = 4 * cs;
    double lo = 0, hi = std::sqrt(0.9 * width * height / std::max(area, 1e-300));
    std::vector<Placement> placed;
    for (int it = 0; it < 12; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (bitmap_pack(charts, order, mid, margin, coarse, int(width / coarse),
                        int(height / coarse), &placed))
            lo = mid;
        else
            hi = mid;
    }
    // On the fine grid: down until it fits, then a bisection up to 12 % higher.
    for (int k = 0;
         lo > 0 && !bitmap_pack(charts, order, lo, margin, cs, cols, rows, &placed); ++k)
        lo = k < 20 ? lo * 0.97 : 0;
    hi = lo * 1.12;
    for (int it = 0; it < 4 && lo > 0; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (bitmap_pack(charts, order, mid, margin, cs, cols, rows, &placed))
            lo = mid;
        else
            hi = mid;
    }
    if (lo > 0) bitmap_pack(charts, order, lo, margin, cs, cols, rows, &placed);
    if (!(lo > 0))
        throw std::invalid_argument("a " + std::to_string(width) + "x" +
                                    std::to_string(height) + " atlas cannot hold " +
                                    std::to_string(charts.size()) +
                                    " charts with their gutters; raise --res");

    Atlas atlas;
    atlas.width = width;
    atlas.height = height;
    atlas.texels_per_unit = lo;
    atlas.num_charts = charts.size();
    atlas.corners.resize(crps.num_triangles());
    const double pad = margin + cs;
    for (size_t i = 0; i < charts.size(); ++i) {
        const Chart &c = charts[i];
        const Placement &p = placed[i];
        for (size_t j = 0; j < c.tris.size(); ++j)
            for (int k = 0; k < 3; ++k)
                atlas.corners[c.tris[j]][k] =
                    mask_point(c, c.pos[j][k], p.quarter_turn, lo, pad) +
                    Vec2d{p.x * cs, p.y * cs};
    }
    return atlas;
}

}  // namespace pelage::shader::clonal_mosaic
