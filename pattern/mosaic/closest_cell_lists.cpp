// One triangle's lists of the closest-cell index (Teo 2006 §6.2; see closest_cell.h):
// its subdivisions, each sub-triangle's reach, the candidate cells in its frame, and per
// region the cells within reach, packed into blocks. Part of the index's build
// (closest_cell_build.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "pattern/mosaic/closest_cell_build.h"
#include "pattern/mosaic/subdivision.h"
#include "sim/mesh/closest_point.h"

namespace pelage::pattern::mosaic::detail {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr float inf_f = std::numeric_limits<float>::infinity();
constexpr size_t per_block = CellBlock::size;

using Region = std::array<sim::Vec2d, 3>;

// Subdivisions: rs[l] regions per side searched at run time in layout l, n sub-triangles
// per side built. Fine regions: about one per cell spacing across. Coarse ones: one list
// per triangle while the triangle is at most six cell spacings across (most triangles
// of a typical mesh), as its sub-triangles' lists overlap so much that storing them
// apart costs more cache misses than their shorter scans save (a lower threshold only
// makes the index larger). The reach is computed per sub-triangle of a finer
// n-subdivision (about two per cell spacing, at most 6, nested in both
// r-subdivisions): finer sub-triangles have tighter radii R_S, so the lists are
// shorter, at no cost to a lookup.
struct Subdivisions {
    uint32_t rs[2];
    uint32_t n;
    sim::Vec2d v0, e1, e2;  // the triangle in its frame

    Subdivisions(const sim::CrpsFrame &ft, const BuildScale &scale) {
        const double spacings = 2 * ft.bound_radius / std::max(scale.spacing, 1e-300);
        const uint32_t r_max = std::clamp<uint32_t>(scale.max_subdivision, 1,
                                                    ClosestCellIndex::max_subdivision);
        rs[0] = std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings / 6)), 1,
                                     r_max);
        rs[1] =
            std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings)), 1, r_max);
        // n: about two per spacing, at most 6, a multiple of both r (lcm(r0, r1) <= 6).
        const uint32_t lcm = rs[0] * rs[1] / std::gcd(rs[0], rs[1]);
        const uint32_t fine =
            std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(2 * spacings)), 1, 6);
        n = lcm * ((fine + lcm - 1) / lcm);
        v0 = ft.v[0];
        e1 = ft.v[1] - ft.v[0];
        e2 = ft.v[2] - ft.v[0];
    }
    // Both layouts have the same regions (and so the same lists).
    bool same_layouts() const { return rs[1] == rs[0]; }
    // Barycentric point b of the triangle, in its frame.
    sim::Vec2d at(const std::array<double, 2> &b) const {
        return v0 + e1 * b[0] + e2 * b[1];
    }
    // Region k of an r-subdivision.
    Region region(uint32_t r, uint32_t k) const {
        Region reg{};
        for (uint32_t i = 0; i < r; ++i)
            for (uint32_t j = 0; i + j < r; ++j)
                for (int upper = 0; upper < 2; ++upper) {
                    if (upper && i + j + 1 >= r) continue;
                    if (slot_index(r, i, j, upper) != k) continue;
                    const auto b = sub_triangle(r, i, j, upper);
                    for (int c = 0; c < 3; ++c) reg[c] = at(b[c]);
                }
        return reg;
    }
    // All regions of an r-subdivision, by slot.
    std::array<Region, max_regions> regions(uint32_t r) const {
        std::array<Region, max_regions> regs;
        for (uint32_t i = 0; i < r; ++i)
            for (uint32_t j = 0; i + j < r; ++j)
                for (int upper = 0; upper < 2; ++upper) {
                    if (upper && i + j + 1 >= r) continue;
                    const auto b = sub_triangle(r, i, j, upper);
                    for (int c = 0; c < 3; ++c)
                        regs[slot_index(r, i, j, upper)][c] = at(b[c]);
                }
        return regs;
    }
};

// The triangle's frame as the searches read it, in float.
TriangleFrame frame_of(const Subdivisions &sd) {
    TriangleFrame f = {float(sd.v0.x),
                       float(sd.v0.y),
                       float(sd.e1.x),
                       float(sd.e1.y),
                       float(sd.e2.x),
                       float(sd.e2.y),
                       0};
    f.inv_det = 1.0f / (f.e1x * f.e2y - f.e1y * f.e2x);  // in float, like the searches
    return f;
}

// One sub-triangle S of the n-subdivision.
struct Sub {
    uint32_t region[2];  // the sub-triangles of the r-subdivisions holding this one
    sim::Vec2d v[3], centre;
    double bound = 0;
};

std::vector<Sub> sub_triangles(const Subdivisions &sd) {
    const uint32_t n = sd.n;
    std::vector<Sub> subs;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; i + j < n; ++j)
            for (int upper = 0; upper < 2; ++upper) {
                if (upper && i + j + 1 >= n) continue;
                Sub s;
                const auto b = sub_triangle(n, i, j, upper);
                for (int c = 0; c < 3; ++c) s.v[c] = sd.at(b[c]);
                s.centre = (s.v[0] + s.v[1] + s.v[2]) / 3.0;
                for (int c = 0; c < 3; ++c)
                    s.bound = std::max(s.bound, length(s.v[c] - s.centre));
                for (int l = 0; l < 2; ++l)
                    s.region[l] = slot_at(sd.rs[l], (b[0][0] + b[1][0] + b[2][0]) / 3,
                                          (b[0][1] + b[1][1] + b[2][1]) / 3);
                subs.push_back(s);
            }
    return subs;
}

// The least reach R_S that holds S's three nearest cells over all of S, from the
// candidates of S's region in the layout. For any three cells T, F3(q) <= max_{c in T}
// |q - c| on all of S, and that maximum over the triangle S is reached at one of its
// corners. T = the three nearest to S's centroid or to one of its corners; the tightest
// bound wins. (It is at most d_3 + b_S, the centroid bound.)
double reach_of(const Sub &s, const std::vector<Mapped> &mapped) {
    double reach_needed = inf;
    const sim::Vec2d probes[4] = {s.centre, s.v[0], s.v[1], s.v[2]};
    for (const sim::Vec2d &probe : probes) {
        const Mapped *near[3] = {nullptr, nullptr, nullptr};
        double d[3] = {inf, inf, inf};
        for (const Mapped &m : mapped) {
            const double dk = length(m.p - probe);
            if (dk < d[2]) {
                d[2] = dk;
                near[2] = &m;
                if (d[2] < d[1]) std::swap(d[1], d[2]), std::swap(near[1], near[2]);
                if (d[1] < d[0]) std::swap(d[0], d[1]), std::swap(near[0], near[1]);
            }
        }
        if (!near[2]) continue;  // fewer than three cells within the radius
        double reach = 0;
        for (const Mapped *m : near)
            for (const sim::Vec2d &corner : s.v)
                reach = std::max(reach, length(m->p - corner));
        reach_needed = std::min(reach_needed, reach);
    }
    return reach_needed;
}

// Candidates per layout and region, and each S's reach in each layout.
struct TriangleCandidates {
    std::array<std::array<std::vector<Mapped>, max_regions>, 2> mapped;
    std::vector<std::array<double, 2>> reach;
};

// Geodesic: each cell's windows on t, one position per region. Returns the largest
// reach of an S.
double geodesic_candidates(sim::TriId t, const Subdivisions &sd,
                           const std::vector<Sub> &subs, const Candidates &candidates,
                           TriangleCandidates &tc) {
    const auto ws = candidates.windows->of(t);
    for (int layout = 0; layout < 2; ++layout)
        for (uint32_t k = 0; k < sd.rs[layout] * sd.rs[layout]; ++k) {
            if (layout == 1 && sd.same_layouts()) {
                tc.mapped[1][k] = tc.mapped[0][k];
                continue;
            }
            map_region_candidates(ws, sd.region(sd.rs[layout], k), candidates.cell_tri,
                                  tc.mapped[layout][k]);
        }
    double needed = 0;
    for (size_t i = 0; i < subs.size(); ++i)
        for (int layout = 0; layout < 2; ++layout) {
            tc.reach[i][layout] =
                reach_of(subs[i], tc.mapped[layout][subs[i].region[layout]]);
            needed = std::max(needed, tc.reach[i][layout]);
        }
    return needed;
}

// Unfolding: grow t's unfolding until it holds, for every S, all cells within R_S of
// S. Every cell of the unfolding carried into t's frame once (Teo's F[j→t]), in double.
// When fewer than three cells are reachable the radius doubles up to the size of the
// whole surface, after which the lists hold whatever there is (possibly nothing).
// Returns the largest reach of an S.
double unfolded_candidates(const sim::Crps &crps, sim::TriId t, const BuildScale &scale,
                           const Subdivisions &sd, const std::vector<Sub> &subs,
                           Candidates &candidates, TriangleCandidates &tc) {
    const CellTable &cells = *scale.cells;
    Candidates::Scratch &scratch = candidates.scratch.local();
    std::vector<Mapped> all;
    double needed = 0;
    double radius = scale.initial_radius + crps.frame(t).bound_radius;
    for (int iteration = 0; iteration < 64; ++iteration) {
        sim::unfold_around_triangle(crps, t, radius, scratch.unfolded, scratch.unfold,
                                    candidates.paths);
        all.clear();
        for (const sim::UnfoldedTriangle &u : scratch.unfolded)
            for (uint32_t k = cells.row[u.tri]; k < cells.row[u.tri + 1]; ++k)
                all.push_back({u.to_master.apply({cells.x[k], cells.z[k]}), k, u.tri});
        needed = 0;
        for (size_t i = 0; i < subs.size(); ++i) {
            tc.reach[i][0] = tc.reach[i][1] = reach_of(subs[i], all);
            needed = std::max(needed, tc.reach[i][0]);
        }
        if (needed <= radius || radius >= scale.max_radius) break;
        // A larger radius may reach triangles by other paths: grow with a margin,
        // re-check.
        radius = std::isfinite(needed)
                     ? std::min(needed * 1.0001 + 1e-12, scale.max_radius)
                     : std::min(2 * radius, scale.max_radius);
    }
    for (int layout = 0; layout < 2; ++layout)
        for (uint32_t k = 0; k < sd.rs[layout] * sd.rs[layout]; ++k)
            tc.mapped[layout][k] = all;
    return needed;
}

// A bent entry's windows, appended to the triangle's bent table: the first tagged with
// the cell, the rest `more` (cell_block.h).
void append_bent_windows(const Mapped &m, TriangleLists &o) {
    for (uint32_t k = 0; k < m.num_windows; ++k) {
        const sim::GeodesicWindow &w = m.windows[k].window;
        const bool whole = w.edge == sim::GeodesicWindow::whole_face;
        o.bent_windows.push_back(
            {float(w.source.x), float(w.source.y), float(w.sigma),
             whole ? std::numeric_limits<float>::quiet_NaN() : float(w.x0.x),
             float(w.x0.y), float(w.x1.x), float(w.x1.y),
             k == 0 ? m.cell : BentWindow::more});
    }
}

// Per region: the cells within R_S of one of its S, by distance from it (each cell
// occurs once in a region's candidates), packed five to a block.
struct RegionLists {
    struct Entry {
        double bound;
        const Mapped *m;
    };
    const std::vector<Sub> &subs;
    const std::vector<std::array<double, 2>> &reach;
    double bound_radius;  // the triangle's
    std::vector<Entry> list;
    std::vector<sim::TriId> tris;

    // The region's cells within reach of one of its S, nearest to the region first
    // (ties by cell).
    void select(int layout, uint32_t k, const Region &region,
                const std::vector<Mapped> &mapped) {
        list.clear();
        for (const Mapped &m : mapped)
            for (size_t si = 0; si < subs.size(); ++si) {
                const Sub &s = subs[si];
                const double reach_needed = reach[si][layout];
                // (The distance from S is at least that from its centre less its
                // radius: a cheap test first, with room for its rounding.)
                if (s.region[layout] == k &&
                    length(m.p - s.centre) - s.bound <= reach_needed * (1 + 1e-6) &&
                    sim::point_triangle_distance(m.p, s.v) <= reach_needed * (1 + 1e-9)) {
                    list.push_back(
                        {sim::point_triangle_distance(m.p, region.data()), &m});
                    break;
                }
            }
        std::sort(list.begin(), list.end(), [](const Entry &a, const Entry &b) {
            return a.bound < b.bound || (a.bound == b.bound && a.m->cell < b.m->cell);
        });
    }
    // The list's statistics.
    void count(TriangleLists &o) {
        tris.clear();
        for (const Entry &e : list) tris.push_back(e.m->tri);
        std::sort(tris.begin(), tris.end());
        o.distinct_triangles += std::unique(tris.begin(), tris.end()) - tris.begin();
        o.entries += list.size();
        o.longest = std::max(o.longest, list.size());
    }
    // The list as blocks, padded with (none, +inf).
    void pack(TriangleLists &o) const {
        for (size_t i = 0; i < list.size(); i += per_block) {
            CellBlock b;
            // The bound is rounded down by more than float's error in the scan's
            // distances (positions of size |p| + the triangle's radius), so rounding
            // never prunes the true nearest.
            const double margin =
                1e-5 * (list[i].bound + length(list[i].m->p) + bound_radius);
            const double lower = std::max(0.0, list[i].bound - margin);
            b.bound2 = float(lower * lower * (1 - 1e-6));
            for (size_t l = 0; l < per_block; ++l) {
                const bool real = i + l < list.size();
                b.x[l] = real ? float(list[i + l].m->p.x) : inf_f;
                b.y[l] = real ? float(list[i + l].m->p.y) : inf_f;
                b.cell[l] = real ? list[i + l].m->cell : ClosestCell::none;
                if (real && list[i + l].m->bent) {
                    b.cell[l] = bent_flag | static_cast<uint32_t>(o.bent_windows.size());
                    ++o.bent_entries;
                    append_bent_windows(*list[i + l].m, o);
                }
            }
            o.blocks.push_back(b);
        }
    }
};

// Both layouts' lists, from the candidates and reaches.
void pack_layouts(const Subdivisions &sd, const std::vector<Sub> &subs,
                  const TriangleCandidates &tc, double bound_radius,
                  std::array<TriangleLists, 2> &out) {
    RegionLists lists{subs, tc.reach, bound_radius, {}, {}};
    for (int layout = 0; layout < 2; ++layout) {
        TriangleLists &o = out[layout];
        const uint32_t r = sd.rs[layout];
        o.regions = r;
        if (layout == 1 && sd.same_layouts()) {  // the same lists
            o = out[0];
            break;
        }
        const std::array<Region, max_regions> regions = sd.regions(r);
        for (uint32_t k = 0; k < r * r; ++k) {
            lists.select(layout, k, regions[k], tc.mapped[layout][k]);
            lists.count(o);
            lists.pack(o);
            o.end[k] = static_cast<uint32_t>(o.blocks.size());
        }
    }
}

}  // namespace

double build_triangle_lists(const sim::Crps &crps, sim::TriId t, const BuildScale &scale,
                            Candidates &candidates, std::array<TriangleLists, 2> &out) {
    const sim::CrpsFrame &ft = crps.frame(t);
    const Subdivisions sd(ft, scale);
    out[0].frame = frame_of(sd);
    out[1].frame = out[0].frame;
    const std::vector<Sub> subs = sub_triangles(sd);
    TriangleCandidates tc;
    tc.reach.resize(subs.size());
    double needed = 0;
    if (candidates.windows) {
        needed = geodesic_candidates(t, sd, subs, candidates, tc);
        // Positions beyond the windows' radius are missing: build again, farther
        // (unless the radius already spans the surface: then this is all there is).
        if (needed > candidates.radius[t] &&
            candidates.radius[t] < candidates.max_radius[t])
            return needed;
    } else {
        needed = unfolded_candidates(crps, t, scale, sd, subs, candidates, tc);
    }
    pack_layouts(sd, subs, tc, ft.bound_radius, out);
    return needed;
}

}  // namespace pelage::pattern::mosaic::detail
