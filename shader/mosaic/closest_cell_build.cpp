// Builds the closest-cell index: per triangle, the cell lists of its regions (Teo 2006
// §6.2; see closest_cell.h). The searches are in closest_cell.cpp.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "shader/mosaic/closest_cell.h"
#include "shader/mosaic/subdivision.h"
#include "sim/geodesic/windows_by_face.h"
#include "sim/mesh/closest_point.h"

namespace pelage::shader::mosaic {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr float inf_f = std::numeric_limits<float>::infinity();
constexpr uint32_t invalid_component = 0xffffffffu;

// A cell as a triangle's list sees it: its position in the triangle's frame.
struct Mapped {
    sim::Vec2d p;
    uint32_t cell;
    sim::TriId tri;  // the cell's own triangle (for statistics)
    // Not one straight line over the region (closest_cell.h, bent_flag): the cell's
    // windows on the triangle, for its exact distance.
    bool bent = false;
    const sim::SourcedWindow *windows = nullptr;
    uint32_t num_windows = 0;
};

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
    // Within float precision below (never an impossible, too-short distance) and a
    // thousandth above (reported distances stay within 0.1 % of the exact ones).
    constexpr double fit_below = 1e-6, fit_above = 1e-3;
    constexpr int per_side = 4, samples = (per_side + 1) * (per_side + 2) / 2;
    const int n = static_cast<int>(end - begin);
    // The common case first: the cell's only window on the triangle is straight and
    // covers the whole region (its wedge and the region are convex: the corners tell).
    if (n == 1 && begin->window.sigma == 0 && begin->window.covers(region[0]) &&
        begin->window.covers(region[1]) && begin->window.covers(region[2])) {
        out.p = begin->window.source;
        out.bent = false;
        out.windows = begin;
        out.num_windows = 1;
        return true;
    }
    thread_local std::vector<int> votes;
    thread_local std::vector<char> whole;  // covers the whole region: no test per sample
    votes.assign(n, 0);
    whole.resize(n);
    for (int w = 0; w < n; ++w)
        whole[w] = begin[w].window.covers(region[0]) &&
                   begin[w].window.covers(region[1]) && begin[w].window.covers(region[2]);
    sim::Vec2d q[samples];
    double d[samples];
    int m = 0;
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
            q[m] = x;
            d[m] = best_d;
            ++m;
        }
    if (m == 0) return false;
    const int w =
        static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    const sim::GeodesicWindow &win = begin[w].window;
    // A bent entry keeps all the cell's windows on the triangle (closest_cell.h): one
    // that serves no sample point may still serve points between them.
    out.windows = begin;
    out.num_windows = static_cast<uint32_t>(n);
    // One straight window that stands for the cell over the whole region within float
    // precision below and a hair above (a convex vertex between two unfoldings makes the
    // window's formula slightly longer past it): not bent.
    if (win.sigma == 0) {
        bool fits = true;
        for (int i = 0; i < m && fits; ++i) {
            const double e = length(q[i] - win.source) - d[i];
            fits = e >= -fit_below * d[i] && e <= fit_above * d[i];
        }
        if (fits) {
            out.bent = false;
            out.p = win.source;
            return true;
        }
    }
    out.bent = true;
    const sim::Vec2d centre = (region[0] + region[1] + region[2]) / 3.0;
    const sim::Vec2d away = win.source - centre;
    const double len = length(away);
    sim::Vec2d p =
        win.source + (len > 0 ? away * (win.sigma / len) : sim::Vec2d{win.sigma, 0});
    // Gauss–Newton steps, each halved until it lowers the sum of squares: with samples
    // along a line (a region's corner that few of the cell's wedges reach) the plain
    // step can run off along the line, to a position metres from a centimetre-sized
    // region whose reach then spans the surface.
    auto misfit = [&](sim::Vec2d x) {
        double sum = 0;
        for (int i = 0; i < m; ++i) {
            const double r = length(q[i] - x) - d[i];
            sum += r * r;
        }
        return sum;
    };
    double cost = misfit(p);
    for (int iteration = 0; iteration < 8; ++iteration) {
        // Normal equations of min Σ (|q_i − p| − d_i)² for the step.
        double a11 = 0, a12 = 0, a22 = 0, g1 = 0, g2 = 0;
        for (int i = 0; i < m; ++i) {
            const sim::Vec2d u = p - q[i];
            const double l = length(u);
            if (l <= 0) continue;
            const sim::Vec2d j = u / l;
            const double r = l - d[i];
            a11 += j.x * j.x;
            a12 += j.x * j.y;
            a22 += j.y * j.y;
            g1 += j.x * r;
            g2 += j.y * r;
        }
        const double det = a11 * a22 - a12 * a12;
        if (!(std::abs(det) > 1e-12 * (a11 + a22) * (a11 + a22))) break;
        sim::Vec2d step{-(a22 * g1 - a12 * g2) / det, -(a11 * g2 - a12 * g1) / det};
        double next = misfit(p + step);
        for (int halving = 0; halving < 40 && !(next <= cost); ++halving) {
            step = step * 0.5;
            next = misfit(p + step);
        }
        if (!(next <= cost)) break;
        p += step;
        cost = next;
        if (length(step) <= 1e-12 * (len + win.sigma)) break;
    }
    // Moved away from the region until no sample's fitted distance falls short of the
    // exact one (moving by δ lengthens every distance by nearly δ): when the fit then
    // overshoots nowhere by more than the tolerance either, the position stands for the
    // cell as well as a single window would, and the entry is not bent.
    double shortfall = 0;
    for (int i = 0; i < m; ++i) shortfall = std::max(shortfall, d[i] - length(q[i] - p));
    const sim::Vec2d axis = p - centre;
    const double axis_len = length(axis);
    if (shortfall > 0 && axis_len > 0) {
        const sim::Vec2d moved = p + axis * (shortfall / axis_len);
        bool fits = true;
        for (int i = 0; i < m && fits; ++i) {
            const double e = length(q[i] - moved) - d[i];
            fits = e >= -fit_below * d[i] && e <= fit_above * d[i];
        }
        if (fits) {
            out.p = moved;
            out.bent = false;
            return true;
        }
    } else if (shortfall <= 0) {
        bool fits = true;
        for (int i = 0; i < m && fits; ++i)
            fits = length(q[i] - p) - d[i] <= fit_above * d[i];
        if (fits) {
            out.p = p;
            out.bent = false;
            return true;
        }
    }
    out.p = p;
    return true;
}

// The surface's connected components (through the edges paths cross): no path leaves
// one, so no reach on a triangle exceeds its component's size.
struct Components {
    std::vector<uint32_t> of;  // per triangle
    // Per component: the sum of its triangles' diameters (a shortest path crosses each
    // face at most once, so it is never longer) and its cells.
    std::vector<double> size;
    std::vector<uint32_t> cells;
    // Per component, its cells' indices (ascending).
    std::vector<uint32_t> cell_row, cell_list;
};

Components components(const sim::GeodesicMesh &mesh, const CellTable &cells) {
    const sim::Crps &crps = mesh.crps();
    const size_t nt = crps.num_triangles();
    Components c;
    c.of.assign(nt, invalid_component);
    std::vector<sim::TriId> stack;
    for (sim::TriId seed = 0; seed < nt; ++seed) {
        if (c.of[seed] != invalid_component) continue;
        const uint32_t id = static_cast<uint32_t>(c.size.size());
        c.size.push_back(0);
        c.cells.push_back(0);
        c.of[seed] = id;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const sim::TriId t = stack.back();
            stack.pop_back();
            c.size[id] += 2 * crps.frame(t).bound_radius;
            c.cells[id] += cells.row[t + 1] - cells.row[t];
            for (int k = 0; k < 3; ++k) {
                const sim::TriId u = mesh.link(t, k).across;
                if (u != sim::invalid_id && c.of[u] == invalid_component) {
                    c.of[u] = id;
                    stack.push_back(u);
                }
            }
        }
    }
    c.cell_row.assign(c.size.size() + 1, 0);
    for (size_t i = 0; i < c.size.size(); ++i)
        c.cell_row[i + 1] = c.cell_row[i] + c.cells[i];
    c.cell_list.resize(cells.size());
    std::vector<uint32_t> fill(c.cell_row.begin(), c.cell_row.end() - 1);
    for (sim::TriId t = 0; t < nt; ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
            c.cell_list[fill[c.of[t]]++] = k;
    return c;
}

// The radius each source must propagate to for the pending triangles' windows to be
// complete within their radii: the largest radius of a pending triangle of its component
// whose bounding sphere it lies within that radius of (3D distance never exceeds the
// geodesic one). 0 for the others: they do not propagate. Sources are found through a
// grid of cells `cell` wide, or by scanning the component when that visits fewer.
void reaching_sources(const sim::Crps &crps, const Components &comps,
                      std::span<const sim::SurfacePoint> sources,
                      std::span<const uint8_t> pending, std::span<const double> radius,
                      double cell, std::vector<double> &source_radius) {
    const size_t nt = crps.num_triangles();
    std::vector<sim::Vec3d> at(sources.size());
    tbb::parallel_for(size_t(0), sources.size(), [&](size_t i) {
        at[i] = crps.to_3d(sources[i].tri, sources[i].p);
    });
    auto key = [cell](sim::Vec3d p) {
        return std::array<int64_t, 3>{int64_t(std::floor(p.x / cell)),
                                      int64_t(std::floor(p.y / cell)),
                                      int64_t(std::floor(p.z / cell))};
    };
    auto pack = [](const std::array<int64_t, 3> &k) {
        return (uint64_t(k[0] & 0x1fffff) << 42) | (uint64_t(k[1] & 0x1fffff) << 21) |
               uint64_t(k[2] & 0x1fffff);
    };
    // Sources sorted by grid cell; each occupied cell's range.
    std::vector<std::pair<uint64_t, uint32_t>> by_cell(sources.size());
    for (size_t i = 0; i < sources.size(); ++i)
        by_cell[i] = {pack(key(at[i])), static_cast<uint32_t>(i)};
    std::sort(by_cell.begin(), by_cell.end());
    std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> range;
    for (size_t i = 0; i < by_cell.size();) {
        size_t j = i;
        while (j < by_cell.size() && by_cell[j].first == by_cell[i].first) ++j;
        range[by_cell[i].first] = {uint32_t(i), uint32_t(j)};
        i = j;
    }
    // Non-negative doubles order as their bits: an atomic maximum without a lock.
    std::vector<std::atomic<uint64_t>> best(sources.size());
    for (auto &b : best) b.store(0, std::memory_order_relaxed);
    auto raise = [&](uint32_t i, double r) {
        const uint64_t bits = std::bit_cast<uint64_t>(r);
        uint64_t cur = best[i].load(std::memory_order_relaxed);
        while (cur < bits && !best[i].compare_exchange_weak(cur, bits)) {
        }
    };
    tbb::parallel_for(size_t(0), nt, [&](size_t t) {
        if (!pending[t]) return;
        const uint32_t comp = comps.of[t];
        const sim::Vec3d c = crps.to_3d(static_cast<sim::TriId>(t), {0, 0});
        const double r = radius[t], reach = r + crps.frame(t).bound_radius;
        auto consider = [&](uint32_t i) {
            if (comps.of[sources[i].tri] == comp && length(at[i] - c) <= reach)
                raise(i, r);
        };
        const auto lo = key(c - sim::Vec3d{reach, reach, reach});
        const auto hi = key(c + sim::Vec3d{reach, reach, reach});
        const double boxes = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) *
                             double(hi[2] - lo[2] + 1);
        if (boxes >= comps.cells[comp]) {
            for (uint32_t k = comps.cell_row[comp]; k < comps.cell_row[comp + 1]; ++k)
                consider(comps.cell_list[k]);
            return;
        }
        for (int64_t x = lo[0]; x <= hi[0]; ++x)
            for (int64_t y = lo[1]; y <= hi[1]; ++y)
                for (int64_t z = lo[2]; z <= hi[2]; ++z) {
                    const auto it = range.find(pack({x, y, z}));
                    if (it == range.end()) continue;
                    for (uint32_t k = it->second.first; k < it->second.second; ++k)
                        consider(by_cell[k].second);
                }
    });
    source_radius.resize(sources.size());
    for (size_t i = 0; i < sources.size(); ++i)
        source_radius[i] = std::bit_cast<double>(best[i].load(std::memory_order_relaxed));
}

}  // namespace

// Where build_triangle() finds a triangle's cells: the geodesic windows of every cell
// (grouped by triangle), or, for the unfolding neighbourhoods, per-thread unfolding
// state.
struct ClosestCellIndex::Candidates {
    const sim::WindowsByFace *windows = nullptr;
    // Per triangle: the radius within which its windows are complete (every cell that
    // reaches it by a path of at most that length is there), and the most any reach on
    // it can need (its component's size).
    std::vector<double> radius, max_radius;
    std::vector<sim::TriId> cell_tri;  // each cell's triangle
    sim::UnfoldPaths paths = sim::UnfoldPaths::edges_only;
    struct Scratch {
        sim::UnfoldScratch unfold;
        std::vector<sim::UnfoldedTriangle> unfolded;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
};

// One triangle's lists for one choice of regions.
struct ClosestCellIndex::Built {
    Frame frame{};
    uint32_t regions = 1;  // sub-triangles per side searched at run time
    std::array<uint32_t, max_subdivision * max_subdivision>
        end{};  // each list's, in blocks
    std::vector<Block> blocks;
    std::vector<BentWindow> bent_windows;  // indexed by the blocks' bent entries, from 0
    size_t bent_entries = 0;
    size_t entries = 0, distinct_triangles = 0, longest = 0;
};

ClosestCellIndex::ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                                   const ClosestCellOptions &options)
    : m_cells(&cells), m_options(options), m_lanes(lane_scanners(options.wide_lanes)) {
    m_stats.lanes = m_lanes.lanes;
    const auto t0 = std::chrono::steady_clock::now();
    const size_t nt = crps.num_triangles();
    double area = 0;
    for (sim::TriId t = 0; t < nt; ++t) area += crps.frame(t).area;
    m_spacing = std::sqrt(area / std::max<size_t>(cells.size(), 1));
    // First guess of the reach: two mean cell spacings (Walter's r with w_r = 2).
    m_initial_radius = 2.0 * m_spacing;
    // No unfolding reaches farther than the sum of all triangles' diameters.
    for (sim::TriId t = 0; t < nt; ++t) m_max_radius += 2 * crps.frame(t).bound_radius;

    // --- Per triangle, in parallel; then concatenated in triangle order ---
    // Both layouts: [0] coarse regions (few, long lists), [1] fine (as many regions as
    // cell spacings across, up to 3 per side).
    std::vector<std::array<Built, 2>> built(nt);
    Candidates candidates;
    candidates.paths = m_options.neighbourhood == Neighbourhood::unfolding_teo
                           ? sim::UnfoldPaths::edges_and_vertices
                           : sim::UnfoldPaths::edges_only;
    if (m_options.neighbourhood != Neighbourhood::geodesic) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 64), [&](const auto &range) {
            for (size_t t = range.begin(); t != range.end(); ++t)
                build_triangle(crps, static_cast<sim::TriId>(t), candidates, built[t]);
        });
    } else {
        // Every cell's windows within a radius; triangles whose lists need a longer
        // reach (sparse cells, fewer than three in range) are built again from longer
        // windows of the cells that can reach them, each triangle's radius growing on
        // its own up to the size of its component (no path leaves a component).
        const sim::GeodesicMesh geodesic_mesh(crps);
        std::vector<sim::SurfacePoint> sources(cells.size());
        candidates.cell_tri.resize(cells.size());
        for (sim::TriId t = 0; t < nt; ++t)
            for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k) {
                sources[k] = {t, {cells.x[k], cells.z[k]}};
                candidates.cell_tri[k] = t;
            }
        const Components comps = components(geodesic_mesh, cells);
        // Where a component holds fewer than three cells, its triangles' lists hold all
        // of them: its whole size at once.
        auto first_radius = [&](uint32_t comp) {
            return comps.cells[comp] < 3 ? comps.size[comp] : m_initial_radius;
        };
        candidates.radius.resize(nt);
        candidates.max_radius.resize(nt);
        for (size_t t = 0; t < nt; ++t) {
            candidates.max_radius[t] = comps.size[comps.of[t]];
            candidates.radius[t] = first_radius(comps.of[t]);
        }
        sim::WindowsByFace windows;
        candidates.windows = &windows;
        std::vector<uint8_t> pending(nt, 1);
        std::vector<double> needed(nt, 0);
        std::vector<double> source_radius(cells.size());
        for (size_t i = 0; i < cells.size(); ++i)
            source_radius[i] = first_radius(comps.of[sources[i].tri]);
        for (int round = 0;; ++round) {
            windows.build(geodesic_mesh, sources, source_radius,
                          round == 0 ? std::span<const uint8_t>() : pending);
            m_stats.geodesic_windows = std::max(m_stats.geodesic_windows, windows.size());
            m_stats.geodesic_bytes = std::max(m_stats.geodesic_bytes, windows.bytes());
            m_stats.geodesic_work += windows.settled();
            tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 16), [&](const auto &r) {
                for (size_t t = r.begin(); t != r.end(); ++t)
                    if (pending[t])
                        needed[t] = build_triangle(crps, static_cast<sim::TriId>(t),
                                                   candidates, built[t]);
            });
            m_stats.geodesic_rounds = round + 1;
            size_t short_of = 0;
            for (size_t t = 0; t < nt; ++t) {
                const double have = candidates.radius[t], most = candidates.max_radius[t];
                pending[t] = pending[t] && needed[t] > have && have < most;
                m_stats.geodesic_radius = std::max(m_stats.geodesic_radius, have);
                if (!pending[t]) continue;
                ++short_of;
                candidates.radius[t] = std::isfinite(needed[t])
                                           ? std::min(needed[t] * 1.0001 + 1e-12, most)
                                           : std::min(2 * have, most);
            }
            if (short_of == 0) break;
            reaching_sources(crps, comps, sources, pending, candidates.radius,
                             2 * m_initial_radius, source_radius);
        }
    }

    // Fine regions scan fewer cells, coarse ones need less memory: fine while the whole
    // index stays within the budget (then it mostly stays in cache anyway).
    size_t blocks_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) blocks_of_layout[l] += b[l].blocks.size();
    size_t regions_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) regions_of_layout[l] += b[l].regions * b[l].regions;
    const size_t fixed = nt * sizeof(Frame) + (nt + 1) * sizeof(uint32_t) +
                         (regions_of_layout[1] + 1) * sizeof(uint32_t);
    const int layout =
        fixed + blocks_of_layout[1] * sizeof(Block) <= m_options.fine_regions_max_bytes;
    m_stats.fine_regions = layout == 1;
    size_t total_blocks = blocks_of_layout[layout], lists = 0, entries = 0, distinct = 0;
    if (total_blocks >= (size_t(1) << 30))
        throw std::length_error("closest-cell index: more than 2^30 candidate blocks");
    m_frames.resize(nt);
    m_first_region.resize(nt + 1);
    m_region_block.reserve(regions_of_layout[layout] + 1);
    m_blocks.reserve(total_blocks);
    for (size_t t = 0; t < nt; ++t) {
        Built &b = built[t][layout];
        m_frames[t] = b.frame;
        m_first_region[t] = static_cast<uint32_t>(m_region_block.size()) << 2 | b.regions;
        const uint32_t first = static_cast<uint32_t>(m_blocks.size());
        for (uint32_t k = 0; k < b.regions * b.regions; ++k)
            m_region_block.push_back(first + (k ? b.end[k - 1] : 0));
        const uint32_t bent_offset = static_cast<uint32_t>(m_bent_windows.size());
        if (m_bent_windows.size() + b.bent_windows.size() >= bent_flag)
            throw std::length_error("closest-cell index: more than 2^31 bent windows");
        for (Block &blk : b.blocks)
            for (uint32_t &c : blk.cell)
                if (c != ClosestCell::none && (c & bent_flag)) c += bent_offset;
        m_stats.bent_entries += b.bent_entries;
        m_bent_windows.insert(m_bent_windows.end(), b.bent_windows.begin(),
                              b.bent_windows.end());
        m_blocks.insert(m_blocks.end(), b.blocks.begin(), b.blocks.end());
        m_stats.triangles_without_cells_in_reach += b.entries == 0;
        m_stats.triangles_with_regions += b.regions > 1;
        m_stats.max_candidate_cells = std::max(m_stats.max_candidate_cells, b.longest);
        lists += b.regions * b.regions;
        entries += b.entries;
        distinct += b.distinct_triangles;
        built[t] = {};
    }
    m_first_region[nt] = static_cast<uint32_t>(m_region_block.size()) << 2 | 1;
    m_region_block.push_back(static_cast<uint32_t>(m_blocks.size()));
    m_stats.mean_candidates = lists ? double(distinct) / lists : 0;
    m_stats.mean_candidate_cells = lists ? double(entries) / lists : 0;
    m_stats.bytes =
        m_frames.size() * sizeof(Frame) + m_first_region.size() * sizeof(uint32_t) +
        m_region_block.size() * sizeof(uint32_t) + m_blocks.size() * sizeof(Block) +
        m_bent_windows.size() * sizeof(BentWindow);
    m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double ClosestCellIndex::build_triangle(const sim::Crps &crps, sim::TriId t,
                                        Candidates &candidates,
                                        std::array<Built, 2> &out) const {
    const CellTable &cells = *m_cells;
    const sim::CrpsFrame &ft = crps.frame(t);

    // --- Subdivisions: r regions per side searched at run time, n per side built ---
    // Fine regions: about one per cell spacing across. Coarse ones: one list per
    // triangle while the triangle is at most six cell spacings across (most triangles
    // of a typical mesh), as its sub-triangles' lists overlap so much that storing them
    // apart costs more cache misses than their shorter scans save (a lower threshold
    // only makes the index larger). The reach is computed per sub-triangle of a finer
    // n-subdivision (about two per cell spacing, at most 6, nested in both
    // r-subdivisions): finer sub-triangles have tighter radii R_S, so the lists are
    // shorter, at no cost to a lookup.
    const double spacings = 2 * ft.bound_radius / std::max(m_spacing, 1e-300);
    const uint32_t r_max =
        std::clamp<uint32_t>(m_options.max_subdivision, 1, max_subdivision);
    const uint32_t rs[2] = {
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings / 6)), 1, r_max),
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(spacings)), 1, r_max)};
    // n: about two per spacing, at most 6, a multiple of both r (lcm(r0, r1) <= 6).
    const uint32_t lcm = rs[0] * rs[1] / std::gcd(rs[0], rs[1]);
    const uint32_t fine =
        std::clamp<uint32_t>(static_cast<uint32_t>(std::ceil(2 * spacings)), 1, 6);
    const uint32_t n = lcm * ((fine + lcm - 1) / lcm);
    const sim::Vec2d v0 = ft.v[0], e1 = ft.v[1] - ft.v[0], e2 = ft.v[2] - ft.v[0];
    {
        Frame &f = out[0].frame;
        f = {float(v0.x),
             float(v0.y),
             float(e1.x),
             float(e1.y),
             float(e2.x),
             float(e2.y),
             0};
        f.inv_det =
            1.0f / (f.e1x * f.e2y - f.e1y * f.e2x);  // in float, like the searches
        out[1].frame = f;
    }
    struct Sub {
        uint32_t region[2];  // the sub-triangles of the r-subdivisions holding this one
        sim::Vec2d v[3], centre;
        double bound = 0;
    };
    std::vector<Sub> subs;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; i + j < n; ++j)
            for (int upper = 0; upper < 2; ++upper) {
                if (upper && i + j + 1 >= n) continue;
                Sub s;
                const auto b = sub_triangle(n, i, j, upper);
                for (int c = 0; c < 3; ++c) s.v[c] = v0 + e1 * b[c][0] + e2 * b[c][1];
                s.centre = (s.v[0] + s.v[1] + s.v[2]) / 3.0;
                for (int c = 0; c < 3; ++c)
                    s.bound = std::max(s.bound, length(s.v[c] - s.centre));
                for (int l = 0; l < 2; ++l)
                    s.region[l] = slot_at(rs[l], (b[0][0] + b[1][0] + b[2][0]) / 3,
                                          (b[0][1] + b[1][1] + b[2][1]) / 3);
                subs.push_back(s);
            }

    // Region k of an r-subdivision, as a triangle in t's frame.
    auto region_of = [&](uint32_t r, uint32_t k) {
        std::array<sim::Vec2d, 3> reg{};
        for (uint32_t i = 0; i < r; ++i)
            for (uint32_t j = 0; i + j < r; ++j)
                for (int upper = 0; upper < 2; ++upper) {
                    if (upper && i + j + 1 >= r) continue;
                    if (slot_index(r, i, j, upper) != k) continue;
                    const auto b = sub_triangle(r, i, j, upper);
                    for (int c = 0; c < 3; ++c) reg[c] = v0 + e1 * b[c][0] + e2 * b[c][1];
                }
        return reg;
    };

    // For every S, the least reach R_S that holds its three nearest cells over all of
    // S, from the candidates of S's region in the layout.
    // For any three cells T, F3(q) <= max_{c in T} |q - c| on all of S, and that maximum
    // over the triangle S is reached at one of its corners. T = the three nearest to S's
    // centroid or to one of its corners; the tightest bound wins. (It is at most
    // d_3 + b_S, the centroid bound.)
    auto reach_of = [](const Sub &s, const std::vector<Mapped> &mapped) {
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
    };

    // Candidates per layout and region, and each S's reach in each layout.
    std::array<std::array<std::vector<Mapped>, max_subdivision * max_subdivision>, 2>
        mapped;
    std::vector<std::array<double, 2>> reach(subs.size());
    double needed = 0;
    if (candidates.windows) {
        // Geodesic: each cell's windows on t, one position per region.
        struct Group {
            size_t begin, end;
            double lower;
        };
        std::vector<Group> groups;
        const auto ws = candidates.windows->of(t);
        for (int layout = 0; layout < 2; ++layout)
            for (uint32_t k = 0; k < rs[layout] * rs[layout]; ++k) {
                if (layout == 1 && rs[1] == rs[0]) {  // the same regions
                    mapped[1][k] = mapped[0][k];
                    continue;
                }
                const auto region = region_of(rs[layout], k);
                auto &list = mapped[layout][k];
                // Cells that cannot be among the three nearest anywhere in the region
                // are skipped before their positions are fitted: a cell's distance over
                // the region is at least its windows' least σ + |region − s|, and the
                // third-nearest distance at most the one at the centre plus the way from
                // the centre to the farthest corner.
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
                        lower = std::min(lower, w.sigma + sim::point_triangle_distance(
                                                              w.source, region.data()));
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
                for (const Group &g : groups) {
                    if (g.lower > cut) continue;
                    Mapped m;
                    m.cell = ws[g.begin].source;
                    m.tri = candidates.cell_tri[m.cell];
                    if (representative(ws.data() + g.begin, ws.data() + g.end, region, m))
                        list.push_back(m);
                }
            }
        for (size_t i = 0; i < subs.size(); ++i)
            for (int layout = 0; layout < 2; ++layout) {
                reach[i][layout] =
                    reach_of(subs[i], mapped[layout][subs[i].region[layout]]);
                needed = std::max(needed, reach[i][layout]);
            }
        // Positions beyond the windows' radius are missing: build again, farther
        // (unless the radius already spans the surface: then this is all there is).
        if (needed > candidates.radius[t] &&
            candidates.radius[t] < candidates.max_radius[t])
            return needed;
    } else {
        // Unfolding: grow t's unfolding until it holds, for every S, all cells within
        // R_S of S. Every cell of the unfolding carried into t's frame once (Teo's
        // F[j→t]), in double. When fewer than three cells are reachable the radius
        // doubles up to the size of the whole surface, after which the lists hold
        // whatever there is (possibly nothing).
        Candidates::Scratch &scratch = candidates.scratch.local();
        std::vector<Mapped> all;
        double radius = m_initial_radius + ft.bound_radius;
        for (int iteration = 0; iteration < 64; ++iteration) {
            sim::unfold_around_triangle(crps, t, radius, scratch.unfolded, scratch.unfold,
                                        candidates.paths);
            all.clear();
            for (const sim::UnfoldedTriangle &u : scratch.unfolded)
                for (uint32_t k = cells.row[u.tri]; k < cells.row[u.tri + 1]; ++k)
                    all.push_back(
                        {u.to_master.apply({cells.x[k], cells.z[k]}), k, u.tri});
            needed = 0;
            for (size_t i = 0; i < subs.size(); ++i) {
                reach[i][0] = reach[i][1] = reach_of(subs[i], all);
                needed = std::max(needed, reach[i][0]);
            }
            if (needed <= radius || radius >= m_max_radius) break;
            // A larger radius may reach triangles by other paths: grow with a margin,
            // re-check.
            radius = std::isfinite(needed)
                         ? std::min(needed * 1.0001 + 1e-12, m_max_radius)
                         : std::min(2 * radius, m_max_radius);
        }
        for (int layout = 0; layout < 2; ++layout)
            for (uint32_t k = 0; k < rs[layout] * rs[layout]; ++k)
                mapped[layout][k] = all;
    }

    // --- Per region: the cells within R_S of one of its S, by distance from it ---
    // (Each cell occurs once in a region's candidates.)
    struct Entry {
        double bound;
        const Mapped *m;
    };
    std::vector<Entry> list;
    std::vector<sim::TriId> tris;
    for (int layout = 0; layout < 2; ++layout) {
        Built &o = out[layout];
        const uint32_t r = rs[layout];
        o.regions = r;
        if (layout == 1 && rs[1] == rs[0]) {  // the same lists
            o = out[0];
            break;
        }
        std::array<std::array<sim::Vec2d, 3>, max_subdivision * max_subdivision> regions;
        for (uint32_t i = 0; i < r; ++i)
            for (uint32_t j = 0; i + j < r; ++j)
                for (int upper = 0; upper < 2; ++upper) {
                    if (upper && i + j + 1 >= r) continue;
                    const auto b = sub_triangle(r, i, j, upper);
                    for (int c = 0; c < 3; ++c)
                        regions[slot_index(r, i, j, upper)][c] =
                            v0 + e1 * b[c][0] + e2 * b[c][1];
                }
        for (uint32_t k = 0; k < r * r; ++k) {
            const std::array<sim::Vec2d, 3> &region = regions[k];
            list.clear();
            for (const Mapped &m : mapped[layout][k])
                for (size_t si = 0; si < subs.size(); ++si) {
                    const Sub &s = subs[si];
                    const double reach_needed = reach[si][layout];
                    // (The distance from S is at least that from its centre less its
                    // radius: a cheap test first, with room for its rounding.)
                    if (s.region[layout] == k &&
                        length(m.p - s.centre) - s.bound <= reach_needed * (1 + 1e-6) &&
                        sim::point_triangle_distance(m.p, s.v) <=
                            reach_needed * (1 + 1e-9)) {
                        list.push_back(
                            {sim::point_triangle_distance(m.p, region.data()), &m});
                        break;
                    }
                }
            std::sort(list.begin(), list.end(), [](const Entry &a, const Entry &b) {
                return a.bound < b.bound || (a.bound == b.bound && a.m->cell < b.m->cell);
            });
            tris.clear();
            for (const Entry &e : list) tris.push_back(e.m->tri);
            std::sort(tris.begin(), tris.end());
            o.distinct_triangles += std::unique(tris.begin(), tris.end()) - tris.begin();
            o.entries += list.size();
            o.longest = std::max(o.longest, list.size());
            for (size_t i = 0; i < list.size(); i += per_block) {
                Block b;
                // The bound is rounded down by more than float's error in the scan's
                // distances (positions of size |p| + the triangle's radius), so rounding
                // never prunes the true nearest.
                const double margin =
                    1e-5 * (list[i].bound + length(list[i].m->p) + ft.bound_radius);
                const double lower = std::max(0.0, list[i].bound - margin);
                b.bound2 = float(lower * lower * (1 - 1e-6));
                for (size_t l = 0; l < per_block; ++l) {
                    const bool real = i + l < list.size();
                    b.x[l] = real ? float(list[i + l].m->p.x) : inf_f;
                    b.y[l] = real ? float(list[i + l].m->p.y) : inf_f;
                    b.cell[l] = real ? list[i + l].m->cell : ClosestCell::none;
                    if (real && list[i + l].m->bent) {
                        const Mapped &m = *list[i + l].m;
                        b.cell[l] =
                            bent_flag | static_cast<uint32_t>(o.bent_windows.size());
                        ++o.bent_entries;
                        for (uint32_t k = 0; k < m.num_windows; ++k) {
                            const sim::GeodesicWindow &w = m.windows[k].window;
                            const bool whole = w.edge == sim::GeodesicWindow::whole_face;
                            o.bent_windows.push_back(
                                {float(w.source.x), float(w.source.y), float(w.sigma),
                                 whole ? std::numeric_limits<float>::quiet_NaN()
                                       : float(w.x0.x),
                                 float(w.x0.y), float(w.x1.x), float(w.x1.y),
                                 k == 0 ? m.cell : BentWindow::more});
                        }
                    }
                }
                o.blocks.push_back(b);
            }
            o.end[k] = static_cast<uint32_t>(o.blocks.size());
        }
    }
    return needed;
}

}  // namespace pelage::shader::mosaic
