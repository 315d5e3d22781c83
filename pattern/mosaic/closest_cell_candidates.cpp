// Where a triangle's candidate cells sit in its frame, for the geodesic neighbourhood
// (closest_cell.h): per region, the cells that can be among its three nearest, each at
// the position that stands for its geodesic distance over the region. Part of the
// index's build (closest_cell_build.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pattern/mosaic/closest_cell_build.h"
#include "sim/mesh/closest_point.h"

namespace pelage::pattern::mosaic::detail {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Within float precision below (never an impossible, too-short distance) and a
// thousandth above (reported distances stay within 0.1 % of the exact ones).
constexpr double fit_below = 1e-6, fit_above = 1e-3;
// The region's sample points: a 4-per-side barycentric grid.
constexpr int per_side = 4, max_samples = (per_side + 1) * (per_side + 2) / 2;

// The region's sample points some window of the cell reaches, with their exact
// distances: what a position must reproduce.
struct ExactSamples {
    sim::Vec2d q[max_samples];
    double d[max_samples];
    int m = 0;

    // Σ (|q_i − x| − d_i)², the sum of squares the fit lowers.
    double misfit(sim::Vec2d x) const {
        double sum = 0;
        for (int i = 0; i < m; ++i) {
            const double r = length(q[i] - x) - d[i];
            sum += r * r;
        }
        return sum;
    }
    // Every straight-line distance from p within float precision below and the
    // tolerance above the exact one.
    bool fits(sim::Vec2d p) const {
        bool ok = true;
        for (int i = 0; i < m && ok; ++i) {
            const double e = length(q[i] - p) - d[i];
            ok = e >= -fit_below * d[i] && e <= fit_above * d[i];
        }
        return ok;
    }
    // No straight-line distance from p beyond the tolerance above the exact one.
    bool fits_above(sim::Vec2d p) const {
        bool ok = true;
        for (int i = 0; i < m && ok; ++i)
            ok = length(q[i] - p) - d[i] <= fit_above * d[i];
        return ok;
    }
};

// The window's wedge holds the whole region: the wedge and the region are convex, so
// the corners tell.
bool covers_region(const sim::GeodesicWindow &w,
                   const std::array<sim::Vec2d, 3> &region) {
    return w.covers(region[0]) && w.covers(region[1]) && w.covers(region[2]);
}

// The exact distance at each sample point: the least σ + |q − s| over the cell's n
// windows whose wedge holds q (sim/geodesic/window_propagation.h). Returns the window
// that serves most samples, or -1 when no window reaches any.
int sample_exact_distances(const sim::SourcedWindow *begin, int n,
                           const std::array<sim::Vec2d, 3> &region, ExactSamples &s) {
    thread_local std::vector<int> votes;
    thread_local std::vector<char> whole;  // covers the whole region: no test per sample
    votes.assign(n, 0);
    whole.resize(n);
    for (int w = 0; w < n; ++w) whole[w] = covers_region(begin[w].window, region);
    for (int i = 0; i <= per_side; ++i)
        for (int j = 0; i + j <= per_side; ++j) {
            const double b1 = double(i) / per_side, b2 = double(j) / per_side;
            const sim::Vec2d x =
                region[0] * (1 - b1 - b2) + region[1] * b1 + region[2] * b2;
            int best = -1;
            double best_d = inf;
            for (int w = 0; w < n; ++w) {
                const double dw = begin[w].window.distance(x);
                if (dw < best_d && (whole[w] || begin[w].window.covers(x)))
                    best_d = dw, best = w;
            }
            if (best < 0) continue;
            ++votes[best];
            s.q[s.m] = x;
            s.d[s.m] = best_d;
            ++s.m;
        }
    if (s.m == 0) return -1;
    return static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

// The least-squares position from p: Gauss–Newton steps, each halved until it lowers
// the sum of squares. With samples along a line (a region's corner that few of the
// cell's wedges reach) the plain step can run off along the line, to a position metres
// from a centimetre-sized region whose reach then spans the surface. `len` and `sigma`
// set the step too small to go on with.
sim::Vec2d fit_position(const ExactSamples &s, sim::Vec2d p, double len, double sigma) {
    double cost = s.misfit(p);
    for (int iteration = 0; iteration < 8; ++iteration) {
        // Normal equations of min Σ (|q_i − p| − d_i)² for the step.
        double a11 = 0, a12 = 0, a22 = 0, g1 = 0, g2 = 0;
        for (int i = 0; i < s.m; ++i) {
            const sim::Vec2d u = p - s.q[i];
            const double l = length(u);
            if (l <= 0) continue;
            const sim::Vec2d j = u / l;
            const double r = l - s.d[i];
            a11 += j.x * j.x;
            a12 += j.x * j.y;
            a22 += j.y * j.y;
            g1 += j.x * r;
            g2 += j.y * r;
        }
        const double det = a11 * a22 - a12 * a12;
        if (!(std::abs(det) > 1e-12 * (a11 + a22) * (a11 + a22))) break;
        sim::Vec2d step{-(a22 * g1 - a12 * g2) / det, -(a11 * g2 - a12 * g1) / det};
        double next = s.misfit(p + step);
        for (int halving = 0; halving < 40 && !(next <= cost); ++halving) {
            step = step * 0.5;
            next = s.misfit(p + step);
        }
        if (!(next <= cost)) break;
        p += step;
        cost = next;
        if (length(step) <= 1e-12 * (len + sigma)) break;
    }
    return p;
}

// The fitted position p, moved away from the region until no sample's fitted distance
// falls short of the exact one (moving by δ lengthens every distance by nearly δ): when
// the fit then overshoots nowhere by more than the tolerance either, the position
// stands for the cell as well as a single window would, and the entry is not bent.
// Otherwise the entry stays bent, at p.
void settle_fitted(const ExactSamples &s, sim::Vec2d p, sim::Vec2d centre, Mapped &out) {
    double shortfall = 0;
    for (int i = 0; i < s.m; ++i)
        shortfall = std::max(shortfall, s.d[i] - length(s.q[i] - p));
    const sim::Vec2d axis = p - centre;
    const double axis_len = length(axis);
    if (shortfall > 0 && axis_len > 0) {
        const sim::Vec2d moved = p + axis * (shortfall / axis_len);
        if (s.fits(moved)) {
            out.p = moved;
            out.bent = false;
            return;
        }
    } else if (shortfall <= 0) {
        if (s.fits_above(p)) {
            out.p = p;
            out.bent = false;
            return;
        }
    }
    out.p = p;
}

// The position in t's frame that stands for one cell's geodesic distance over a region.
// The exact distance at the region's sample points (a 4-per-side barycentric grid) is
// the least σ + |q − s| over the cell's windows on t whose wedge holds q
// (sim/geodesic/window_propagation.h). When one straight window (σ = 0) serves every
// sample, its source is the position, exactly. Otherwise — the path bends round a
// pseudo-source, or parts of the region see the cell through different unfoldings —
// the position is the point whose straight-line distances fit the exact ones best
// (least squares, Gauss–Newton from the source of the window serving most samples,
// moved back by its σ away from the region), and the entry is bent: the exact distance
// of a returned cell comes from its windows (closest_cell.h). False when no window
// reaches a sample point.
bool representative(const sim::SourcedWindow *begin, const sim::SourcedWindow *end,
                    const std::array<sim::Vec2d, 3> &region, Mapped &out) {
    const int n = static_cast<int>(end - begin);
    // The common case first: the cell's only window on the triangle is straight and
    // covers the whole region.
    if (n == 1 && begin->window.sigma == 0 && covers_region(begin->window, region)) {
        out.p = begin->window.source;
        out.bent = false;
        out.windows = begin;
        out.num_windows = 1;
        return true;
    }
    ExactSamples s;
    const int w = sample_exact_distances(begin, n, region, s);
    if (w < 0) return false;
    const sim::GeodesicWindow &win = begin[w].window;
    // A bent entry keeps all the cell's windows on the triangle (closest_cell.h): one
    // that serves no sample point may still serve points between them.
    out.windows = begin;
    out.num_windows = static_cast<uint32_t>(n);
    // One straight window that stands for the cell over the whole region within float
    // precision below and a hair above (a convex vertex between two unfoldings makes the
    // window's formula slightly longer past it): not bent.
    if (win.sigma == 0 && s.fits(win.source)) {
        out.bent = false;
        out.p = win.source;
        return true;
    }
    out.bent = true;
    const sim::Vec2d centre = (region[0] + region[1] + region[2]) / 3.0;
    const sim::Vec2d away = win.source - centre;
    const double len = length(away);
    const sim::Vec2d start =
        win.source + (len > 0 ? away * (win.sigma / len) : sim::Vec2d{win.sigma, 0});
    settle_fitted(s, fit_position(s, start, len, win.sigma), centre, out);
    return true;
}

// One cell's run of windows on the triangle, and the least distance over the region
// any of them allows.
struct WindowGroup {
    size_t begin, end;
    double lower;
};

}  // namespace

// Cells that cannot be among the three nearest anywhere in the region are skipped
// before their positions are fitted: a cell's distance over the region is at least its
// windows' least σ + |region − s|, and the third-nearest distance at most the one at
// the centre plus the way from the centre to the farthest corner.
void map_region_candidates(std::span<const sim::SourcedWindow> ws,
                           const std::array<sim::Vec2d, 3> &region,
                           const std::vector<sim::TriId> &cell_tri,
                           std::vector<Mapped> &list) {
    thread_local std::vector<WindowGroup> groups;
    const sim::Vec2d centre = (region[0] + region[1] + region[2]) / 3.0;
    double reach_centre = 0;
    for (const sim::Vec2d &c : region)
        reach_centre = std::max(reach_centre, length(c - centre));
    groups.clear();
    double at_centre[3] = {inf, inf, inf};
    for (size_t i = 0; i < ws.size();) {
        size_t j = i;
        double lower = inf, here = inf;
        for (; j < ws.size() && ws[j].source == ws[i].source; ++j) {
            const sim::GeodesicWindow &w = ws[j].window;
            lower = std::min(
                lower, w.sigma + sim::point_triangle_distance(w.source, region.data()));
            if (w.covers(centre)) here = std::min(here, w.distance(centre));
        }
        groups.push_back({i, j, lower});
        if (here < at_centre[2]) {
            at_centre[2] = here;
            std::sort(at_centre, at_centre + 3);
        }
        i = j;
    }
    const double cut = (at_centre[2] + reach_centre) * (1 + 1e-6);
    for (const WindowGroup &g : groups) {
        if (g.lower > cut) continue;
        Mapped m;
        m.cell = ws[g.begin].source;
        m.tri = cell_tri[m.cell];
        if (representative(ws.data() + g.begin, ws.data() + g.end, region, m))
            list.push_back(m);
    }
}

}  // namespace pelage::pattern::mosaic::detail
