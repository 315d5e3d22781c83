#include "pattern/bake/atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "pattern/bake/atlas_charts.h"
#include "sim/mesh/closest_point.h"

namespace pelage::pattern::bake {
namespace {

using sim::TriId;
using sim::Vec2d;
using Tri2 = std::array<Vec2d, 3>;

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
                if (!cell && sim::point_triangle_distance(
                                 {(x + 0.5) * cs, (y + 0.5) * cs}, q.data()) <= reach)
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
        orient_chart(c);
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

}  // namespace pelage::pattern::bake
