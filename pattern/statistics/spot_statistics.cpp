#include "pattern/statistics/spot_statistics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "sim/core/disjoint_sets.h"

namespace pelage::pattern::statistics {
namespace {

constexpr uint32_t none = mosaic::ClosestCell::none;

// One triangle's barycentric grid of n steps: vertex (i, j) sits at b1 = i/n, b2 = j/n.
struct Grid {
    int n = 1;
    size_t first = 0;  // offset of vertex (0, 0) in the flat array of look-ups
    // Row j holds n + 1 - j vertices; rows before j hold sum_{r<j} (n + 1 - r).
    size_t at(int i, int j) const {
        return first + size_t(j) * size_t(n + 1) - size_t(j) * size_t(j - 1) / 2 +
               size_t(i);
    }
    size_t size() const { return size_t(n + 1) * size_t(n + 2) / 2; }
};

// Calls f(a, b) for every grid edge (along v1 − v0, along v2 − v0 and along v2 − v1).
template <typename F>
void for_each_edge(const Grid &g, F &&f) {
    for (int j = 0; j < g.n; ++j)
        for (int i = 0; i + j < g.n; ++i) {
            f(g.at(i, j), g.at(i + 1, j));
            f(g.at(i, j), g.at(i, j + 1));
            f(g.at(i + 1, j), g.at(i, j + 1));
        }
}

int background_type(const std::vector<sim::CellsFileType> &types) {
    for (size_t k = 0; k < types.size(); ++k)
        if (types[k].name == "B") return int(k);
    return types.size() > 1 ? 1 : -1;
}

// Compressed adjacency of the cells from sorted, unique pairs.
struct Adjacency {
    std::vector<uint32_t> row, nbr;
    Adjacency(size_t n, const std::vector<std::pair<uint32_t, uint32_t>> &pairs)
        : row(n + 1, 0) {
        for (const auto &[a, b] : pairs) ++row[a + 1], ++row[b + 1];
        for (size_t c = 0; c < n; ++c) row[c + 1] += row[c];
        nbr.resize(row[n]);
        std::vector<uint32_t> fill(row.begin(), row.end() - 1);
        for (const auto &[a, b] : pairs) nbr[fill[a]++] = b, nbr[fill[b]++] = a;
    }
};

using CellPairs = std::vector<std::pair<uint32_t, uint32_t>>;

// Every triangle's grid and the nearest cell at each of its vertices.
struct CellSamples {
    std::vector<Grid> grids;        // per triangle
    std::vector<uint32_t> cell_at;  // per grid vertex, `none` off every cell
};

// Every triangle's grid, of step h = sqrt(A/m) / resolution along its longest side, and
// the closest-cell search at each grid vertex, triangles in parallel.
CellSamples sample_cells(const mosaic::MosaicPattern &pattern, double h) {
    const sim::Crps &crps = pattern.surface().crps;
    const size_t nt = crps.num_triangles();
    CellSamples out;
    out.grids.resize(nt);
    size_t total = 0;
    for (size_t t = 0; t < nt; ++t) {
        const auto &v = crps.frame(sim::TriId(t)).v;
        const double longest =
            std::max({length(v[1] - v[0]), length(v[2] - v[0]), length(v[2] - v[1])});
        out.grids[t].n = int(std::clamp(std::ceil(longest / h), 1.0, 4096.0));
        out.grids[t].first = total;
        total += out.grids[t].size();
    }
    out.cell_at.assign(total, none);
    const mosaic::ClosestCellIndex &index = pattern.index();
    auto look_up_triangle = [&](size_t t) {
        const Grid &g = out.grids[t];
        const float inv = 1.0f / float(g.n);
        for (int j = 0; j <= g.n; ++j)
            for (int i = 0; i + j <= g.n; ++i)
                out.cell_at[g.at(i, j)] =
                    index.find_nearest(sim::TriId(t), float(i) * inv, float(j) * inv)
                        .index;
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 16), [&](const auto &range) {
        for (size_t t = range.begin(); t != range.end(); ++t) look_up_triangle(t);
    });
    return out;
}

// Each cell's area (a third of each grid sub-triangle per corner) and the cell pairs
// that share a grid edge, sorted and unique.
void measure_cells(const sim::Crps &crps, const CellSamples &samples,
                   std::vector<double> &cell_area, CellPairs &pairs) {
    const std::vector<uint32_t> &cell_at = samples.cell_at;
    for (size_t t = 0; t < samples.grids.size(); ++t) {
        const Grid &g = samples.grids[t];
        const double third = crps.frame(sim::TriId(t)).area / (3.0 * g.n * g.n);
        auto add = [&](size_t a, size_t b, size_t c) {
            for (size_t k : {a, b, c})
                if (cell_at[k] != none) cell_area[cell_at[k]] += third;
        };
        for (int j = 0; j < g.n; ++j)
            for (int i = 0; i + j < g.n; ++i) {
                add(g.at(i, j), g.at(i + 1, j), g.at(i, j + 1));
                if (i + j < g.n - 1)
                    add(g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1));
            }
        for_each_edge(g, [&](size_t a, size_t b) {
            const uint32_t ca = cell_at[a], cb = cell_at[b];
            if (ca != cb && ca != none && cb != none)
                pairs.emplace_back(std::min(ca, cb), std::max(ca, cb));
        });
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

// Which cells are spot: every type but the background's.
struct SpotTypes {
    const mosaic::CellTable &cells;
    int background;
    bool operator()(uint32_t c) const { return int(cells.type[c]) != background; }
};

// The spots: connected non-background cells, numbered by their first cell.
struct Spots {
    std::vector<uint32_t> of_cell;  // per cell, `none` for background and empty cells
    std::vector<double> area;
    std::vector<size_t> cells;
};

Spots find_spots(const SpotTypes &is_spot, const CellPairs &pairs,
                 const std::vector<double> &cell_area) {
    const size_t m = cell_area.size();
    sim::DisjointSets sets(m);
    for (const auto &[a, b] : pairs)
        if (is_spot(a) && is_spot(b)) sets.unite(a, b);
    Spots spots;
    spots.of_cell.assign(m, none);
    std::vector<uint32_t> spot_id_of_root(m, none);
    for (uint32_t c = 0; c < m; ++c) {
        if (!is_spot(c) || cell_area[c] == 0) continue;
        uint32_t &id = spot_id_of_root[sets.find(c)];
        if (id == none) {
            id = uint32_t(spots.area.size());
            spots.area.push_back(0);
            spots.cells.push_back(0);
        }
        spots.of_cell[c] = id;
        spots.area[id] += cell_area[c];
        ++spots.cells[id];
    }
    return spots;
}

// A corner of a grid sub-triangle: its point in the triangle's frame, its cell and the
// spot of that cell (`none`: background).
struct Corner {
    double x, y;
    uint32_t cell, spot;
};

double distance(double ax, double ay, double bx, double by) {
    return std::hypot(bx - ax, by - ay);
}

// Where the border between the cells of a and b crosses segment ab: the zero of
// f(x) = d(x, a.cell) − d(x, b.cell), which is ≤ 0 at a and ≥ 0 at b, taken linear
// between them (the midpoint when either cell is missing from the triangle's list).
Corner bisector_crossing(const mosaic::ClosestCellIndex &index, sim::TriId t,
                         const Corner &a, const Corner &b) {
    const mosaic::Vec2f pa{float(a.x), float(a.y)}, pb{float(b.x), float(b.y)};
    const double fa = double(index.distance_to_cell(t, pa, a.cell)) -
                      double(index.distance_to_cell(t, pa, b.cell));
    const double fb = double(index.distance_to_cell(t, pb, a.cell)) -
                      double(index.distance_to_cell(t, pb, b.cell));
    double s = 0.5;
    if (std::isfinite(fa) && std::isfinite(fb) && fb - fa > 0)
        s = std::clamp(-fa / (fb - fa), 0.0, 1.0);
    return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), none, none};
}

// Where the spot border crosses side ab of a grid sub-triangle (a and b in different
// spots). The bisector of a's and b's cells is the border only when no third cell
// comes between them, which near every corner of a cell one does (a segment from a cell
// to the one past its neighbour crosses their bisector off the border, at up to half a
// grid step from it). So the cell nearest the bisector's crossing replaces the end of
// its spot, and the crossing is taken again on the shorter segment, until the crossing
// lies between the two ends' own cells.
std::pair<double, double> crossing(const mosaic::ClosestCellIndex &index,
                                   const std::vector<uint32_t> &spot_of_cell,
                                   sim::TriId t, Corner a, Corner b) {
    Corner x = bisector_crossing(index, t, a, b);
    for (int step = 0; step < 4; ++step) {
        const uint32_t c =
            index.find_nearest(t, mosaic::Vec2f{float(x.x), float(x.y)}).index;
        if (c == none || c == a.cell || c == b.cell) break;
        const uint32_t spot = spot_of_cell[c];
        if (spot != a.spot && spot != b.spot) break;
        (spot == a.spot ? a : b) = {x.x, x.y, c, spot};
        x = bisector_crossing(index, t, a, b);
    }
    return {x.x, x.y};
}

// The spot border inside one grid sub-triangle, as (spot, length) pairs appended to
// `out`: the chord between its crossings of the sides whose corners lie in different
// spots (two sides; three where three spots meet, joined through their crossings'
// mean). The crossings are on the border, so the chords are the border's to second
// order in the grid step whatever the sub-triangle's shape.
void border_in(const mosaic::ClosestCellIndex &index,
               const std::vector<uint32_t> &spot_of_cell, sim::TriId t,
               const std::array<Corner, 3> &c,
               std::vector<std::pair<uint32_t, double>> &out) {
    std::array<std::pair<double, double>, 3> at;  // on side k: corners k and k + 1
    std::array<bool, 3> crossed{};
    int sides = 0;
    for (int k = 0; k < 3; ++k) {
        const Corner &a = c[k], &b = c[(k + 1) % 3];
        crossed[k] = a.spot != b.spot;
        if (crossed[k]) at[k] = crossing(index, spot_of_cell, t, a, b), ++sides;
    }
    if (sides == 0) return;
    auto add = [&](int k, double length) {
        const uint32_t sa = c[k].spot, sb = c[(k + 1) % 3].spot;
        if (sa != none) out.emplace_back(sa, length);
        if (sb != none) out.emplace_back(sb, length);
    };
    if (sides == 3) {
        const double jx = (at[0].first + at[1].first + at[2].first) / 3;
        const double jy = (at[0].second + at[1].second + at[2].second) / 3;
        for (int k = 0; k < 3; ++k) add(k, distance(at[k].first, at[k].second, jx, jy));
        return;
    }
    // One corner is alone in its spot: the chord joins the crossings of its two sides.
    const int k = crossed[0] ? 0 : 1, l = crossed[2] ? 2 : 1;
    add(k, distance(at[k].first, at[k].second, at[l].first, at[l].second));
}

// Each spot's perimeter: the length of its border traced through every triangle's grid
// (border_in), triangles in parallel and summed in triangle order.
std::vector<double> spot_perimeters(const mosaic::MosaicPattern &pattern,
                                    const CellSamples &samples, const Spots &spots) {
    const mosaic::ClosestCellIndex &index = pattern.index();
    const std::vector<uint32_t> &cell_at = samples.cell_at;
    const size_t nt = samples.grids.size();
    std::vector<std::vector<std::pair<uint32_t, double>>> pieces(nt);
    auto trace_triangle = [&](size_t t) {
        const Grid &g = samples.grids[t];
        const float inv = 1.0f / float(g.n);
        auto corner = [&](int i, int j) {
            const mosaic::Vec2f p =
                index.point(sim::TriId(t), float(i) * inv, float(j) * inv);
            const uint32_t cell = cell_at[g.at(i, j)];
            return Corner{p.x, p.y, cell, cell == none ? none : spots.of_cell[cell]};
        };
        auto sub_triangle = [&](const std::array<Corner, 3> &c) {
            if (c[0].cell == none || c[1].cell == none || c[2].cell == none) return;
            border_in(index, spots.of_cell, sim::TriId(t), c, pieces[t]);
        };
        for (int j = 0; j < g.n; ++j)
            for (int i = 0; i + j < g.n; ++i) {
                sub_triangle({corner(i, j), corner(i + 1, j), corner(i, j + 1)});
                if (i + j < g.n - 1)
                    sub_triangle(
                        {corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)});
            }
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 16), [&](const auto &range) {
        for (size_t t = range.begin(); t != range.end(); ++t) trace_triangle(t);
    });
    std::vector<double> perimeter(spots.area.size(), 0.0);
    for (const auto &p : pieces)
        for (const auto &[spot, length] : p) perimeter[spot] += length;
    return perimeter;
}

// The spots' area mean and spread, circularity and complexity, and their areas and
// perimeters, largest area first.
void summarise_spot_shapes(const std::vector<double> &spot_area,
                           const std::vector<double> &perimeter, SpotStatistics &s) {
    double sum = 0, sum2 = 0, circ_sum = 0, circ_weighted = 0, circ_area = 0;
    size_t with_border = 0;
    for (size_t k = 0; k < s.spots; ++k) {
        sum += spot_area[k];
        sum2 += spot_area[k] * spot_area[k];
        if (perimeter[k] <= 0) continue;
        const double c =
            4 * std::numbers::pi * spot_area[k] / (perimeter[k] * perimeter[k]);
        circ_sum += c;
        circ_weighted += c * spot_area[k];
        circ_area += spot_area[k];
        ++with_border;
    }
    s.spot_area_mean = sum / double(s.spots);
    s.spot_area_sd = std::sqrt(
        std::max(0.0, sum2 / double(s.spots) - s.spot_area_mean * s.spot_area_mean));
    if (with_border > 0) {
        s.spot_circularity_mean = circ_sum / double(with_border);
        s.spot_complexity = 1 - circ_weighted / circ_area;
    }
    std::vector<size_t> order(s.spots);
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return spot_area[a] > spot_area[b]; });
    for (size_t k : order) {
        s.spot_areas.push_back(spot_area[k]);
        s.spot_perimeters.push_back(perimeter[k]);
    }
}

// The mean number of neighbours per spot: background cells join their nearest spot in
// hops (a multi-source breadth-first search), and two spots whose regions touch are
// neighbours.
double spot_neighbours_mean(const Adjacency &adj, const CellPairs &pairs,
                            const Spots &spots) {
    std::vector<uint32_t> label = spots.of_cell, queue;
    const size_t m = label.size();
    for (uint32_t c = 0; c < m; ++c)
        if (label[c] != none) queue.push_back(c);
    for (size_t head = 0; head < queue.size(); ++head) {
        const uint32_t c = queue[head];
        for (uint32_t k = adj.row[c]; k < adj.row[c + 1]; ++k)
            if (label[adj.nbr[k]] == none) {
                label[adj.nbr[k]] = label[c];
                queue.push_back(adj.nbr[k]);
            }
    }
    std::vector<std::pair<uint32_t, uint32_t>> touching;
    for (const auto &[a, b] : pairs)
        if (label[a] != none && label[b] != none && label[a] != label[b])
            touching.emplace_back(std::min(label[a], label[b]),
                                  std::max(label[a], label[b]));
    std::sort(touching.begin(), touching.end());
    touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
    return 2.0 * double(touching.size()) / double(spots.area.size());
}

// The background: its components, the largest one's share, the share touching a spot.
void measure_background(const SpotTypes &is_spot, const Adjacency &adj,
                        const CellPairs &pairs, const std::vector<double> &cell_area,
                        SpotStatistics &s) {
    const size_t m = cell_area.size();
    sim::DisjointSets bsets(m);
    for (const auto &[a, b] : pairs)
        if (!is_spot(a) && !is_spot(b)) bsets.unite(a, b);
    std::vector<double> component_area(m, 0.0);
    double background = 0, near = 0;
    for (uint32_t c = 0; c < m; ++c) {
        if (is_spot(c) || cell_area[c] == 0) continue;
        background += cell_area[c];
        component_area[bsets.find(c)] += cell_area[c];
        bool touches = false;
        for (uint32_t k = adj.row[c]; k < adj.row[c + 1] && !touches; ++k)
            touches = is_spot(adj.nbr[k]);
        if (touches) near += cell_area[c];
    }
    for (double a : component_area)
        if (a > 0) {
            ++s.background_components;
            s.background_largest_share = std::max(s.background_largest_share, a);
        }
    if (background > 0) {
        s.background_largest_share /= background;
        s.background_near_spot = near / background;
    }
}

}  // namespace

SpotStatistics measure_spot_statistics(const mosaic::MosaicPattern &pattern,
                                       double resolution) {
    SpotStatistics s;
    const sim::Crps &crps = pattern.surface().crps;
    const mosaic::CellTable &cells = pattern.cells();
    const size_t nt = crps.num_triangles(), m = cells.size();
    s.by_type.assign(pattern.types().size(), 0.0);
    for (size_t t = 0; t < nt; ++t) s.area += crps.frame(sim::TriId(t)).area;
    if (m == 0 || nt == 0) return s;

    const double h = std::sqrt(s.area / double(m)) / std::max(resolution, 1.0);
    const CellSamples samples = sample_cells(pattern, h);
    s.grid_points = samples.cell_at.size();

    std::vector<double> cell_area(m, 0.0);
    CellPairs pairs;
    measure_cells(crps, samples, cell_area, pairs);
    for (size_t c = 0; c < m; ++c) s.by_type[cells.type[c]] += cell_area[c] / s.area;

    const SpotTypes is_spot{cells, background_type(pattern.types())};
    const Spots spots = find_spots(is_spot, pairs, cell_area);
    s.spots = spots.area.size();
    for (size_t n : spots.cells) s.largest_spot_cells = std::max(s.largest_spot_cells, n);
    if (s.spots > 0)
        summarise_spot_shapes(spots.area, spot_perimeters(pattern, samples, spots), s);

    const Adjacency adj(m, pairs);
    if (s.spots > 1) s.spot_neighbours_mean = spot_neighbours_mean(adj, pairs, spots);
    if (is_spot.background >= 0) measure_background(is_spot, adj, pairs, cell_area, s);
    return s;
}

double spot_area_quantile(const SpotStatistics &s, double q) {
    const std::vector<double> &v = s.spot_areas;  // descending
    if (v.empty()) return 0;
    const double x = (1 - std::clamp(q, 0.0, 1.0)) * double(v.size() - 1);
    const size_t i = size_t(x);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (v[i + 1] - v[i]) * (x - double(i));
}

}  // namespace pelage::pattern::statistics
