// Builds the closest-cell index (Teo 2006 §6.2; see closest_cell.h): every triangle's
// lists, in parallel (closest_cell_lists.cpp), from the geodesic windows of the cells
// that reach it (grown round by round where they fall short) or from its unfolding; then
// the layout that fits and the lists concatenated in triangle order. The searches are in
// closest_cell.cpp.
#include "pattern/mosaic/closest_cell_build.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "pattern/mosaic/closest_cell.h"
#include "sim/geodesic/windows_by_face.h"

namespace pelage::pattern::mosaic {
namespace {

using detail::BuildScale;
using detail::Candidates;
using detail::TriangleLists;
// Per triangle, both layouts: [0] coarse regions (few, long lists), [1] fine (as many
// regions as cell spacings across, up to 3 per side).
using BuiltLists = std::vector<std::array<TriangleLists, 2>>;

constexpr uint32_t invalid_component = 0xffffffffu;

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

// The scale of the build: the mean cell spacing, the first guess of the reach (two mean
// cell spacings: Walter's r with w_r = 2) and the farthest any unfolding reaches (the sum
// of all triangles' diameters).
BuildScale scale_of(const sim::Crps &crps, const CellTable &cells,
                    const ClosestCellOptions &options) {
    const size_t nt = crps.num_triangles();
    BuildScale s;
    s.cells = &cells;
    s.max_subdivision = options.max_subdivision;
    double area = 0;
    for (sim::TriId t = 0; t < nt; ++t) area += crps.frame(t).area;
    s.spacing = std::sqrt(area / std::max<size_t>(cells.size(), 1));
    s.initial_radius = 2.0 * s.spacing;
    for (sim::TriId t = 0; t < nt; ++t) s.max_radius += 2 * crps.frame(t).bound_radius;
    return s;
}

// The unfolding neighbourhoods: every triangle's lists at once, each growing its own
// unfolding.
void build_unfolded(const sim::Crps &crps, const BuildScale &scale,
                    Candidates &candidates, BuiltLists &built) {
    const size_t nt = crps.num_triangles();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 64), [&](const auto &range) {
        for (size_t t = range.begin(); t != range.end(); ++t)
            detail::build_triangle_lists(crps, static_cast<sim::TriId>(t), scale,
                                         candidates, built[t]);
    });
}

// Every cell as a geodesic source, and each cell's triangle.
std::vector<sim::SurfacePoint> cell_sources(const CellTable &cells, size_t nt,
                                            std::vector<sim::TriId> &cell_tri) {
    std::vector<sim::SurfacePoint> sources(cells.size());
    cell_tri.resize(cells.size());
    for (sim::TriId t = 0; t < nt; ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k) {
            sources[k] = {t, {cells.x[k], cells.z[k]}};
            cell_tri[k] = t;
        }
    return sources;
}

// After a round: the triangles whose lists needed a longer reach than their windows
// have (and less than their component's size) stay pending, with their radii grown
// to it. Returns how many there are.
size_t grow_short_radii(const std::vector<double> &needed, std::vector<uint8_t> &pending,
                        Candidates &candidates, ClosestCellStats &stats) {
    size_t short_of = 0;
    for (size_t t = 0; t < pending.size(); ++t) {
        const double have = candidates.radius[t], most = candidates.max_radius[t];
        pending[t] = pending[t] && needed[t] > have && have < most;
        stats.geodesic_radius = std::max(stats.geodesic_radius, have);
        if (!pending[t]) continue;
        ++short_of;
        candidates.radius[t] = std::isfinite(needed[t])
                                   ? std::min(needed[t] * 1.0001 + 1e-12, most)
                                   : std::min(2 * have, most);
    }
    return short_of;
}

// The geodesic neighbourhood: every cell's windows within a radius; triangles whose
// lists need a longer reach (sparse cells, fewer than three in range) are built again
// from longer windows of the cells that can reach them, each triangle's radius growing
// on its own up to the size of its component (no path leaves a component).
void build_geodesic(const sim::Crps &crps, const BuildScale &scale,
                    Candidates &candidates, BuiltLists &built, ClosestCellStats &stats) {
    const CellTable &cells = *scale.cells;
    const size_t nt = crps.num_triangles();
    const sim::GeodesicMesh geodesic_mesh(crps);
    const std::vector<sim::SurfacePoint> sources =
        cell_sources(cells, nt, candidates.cell_tri);
    const Components comps = components(geodesic_mesh, cells);
    // Where a component holds fewer than three cells, its triangles' lists hold all
    // of them: its whole size at once.
    auto first_radius = [&](uint32_t comp) {
        return comps.cells[comp] < 3 ? comps.size[comp] : scale.initial_radius;
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
        stats.geodesic_windows = std::max(stats.geodesic_windows, windows.size());
        stats.geodesic_bytes = std::max(stats.geodesic_bytes, windows.bytes());
        stats.geodesic_work += windows.settled();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 16), [&](const auto &r) {
            for (size_t t = r.begin(); t != r.end(); ++t)
                if (pending[t])
                    needed[t] = detail::build_triangle_lists(
                        crps, static_cast<sim::TriId>(t), scale, candidates, built[t]);
        });
        stats.geodesic_rounds = round + 1;
        if (grow_short_radii(needed, pending, candidates, stats) == 0) break;
        reaching_sources(crps, comps, sources, pending, candidates.radius,
                         2 * scale.initial_radius, source_radius);
    }
    candidates.windows = nullptr;  // the windows go with this scope
}

// Which layout the index keeps, with its block and region counts. Fine regions scan
// fewer cells, coarse ones need less memory: fine while the whole index stays within
// the budget (then it mostly stays in cache anyway).
struct LayoutChoice {
    int layout;
    size_t blocks, regions;
};

LayoutChoice choose_layout(const BuiltLists &built, size_t budget) {
    const size_t nt = built.size();
    size_t blocks_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) blocks_of_layout[l] += b[l].blocks.size();
    size_t regions_of_layout[2] = {0, 0};
    for (const auto &b : built)
        for (int l = 0; l < 2; ++l) regions_of_layout[l] += b[l].regions * b[l].regions;
    const size_t fixed = nt * sizeof(TriangleFrame) + (nt + 1) * sizeof(uint32_t) +
                         (regions_of_layout[1] + 1) * sizeof(uint32_t);
    const int layout = fixed + blocks_of_layout[1] * sizeof(CellBlock) <= budget;
    return {layout, blocks_of_layout[layout], regions_of_layout[layout]};
}

// The index's arrays (closest_cell.h), filled by concatenate().
struct IndexArrays {
    std::vector<TriangleFrame> &frames;
    std::vector<uint32_t> &first_region, &region_block;
    std::vector<CellBlock> &blocks;
    std::vector<BentWindow> &bent_windows;
};

// Every triangle's lists in the chosen layout, in triangle order: a list's blocks
// offset by those before it, its bent entries by the bent windows before it. Each
// triangle's lists are freed as they are copied.
void concatenate(BuiltLists &built, const LayoutChoice &choice, IndexArrays out,
                 ClosestCellStats &stats) {
    const size_t nt = built.size();
    size_t lists = 0, entries = 0, distinct = 0;
    if (choice.blocks >= (size_t(1) << 30))
        throw std::length_error("closest-cell index: more than 2^30 candidate blocks");
    out.frames.resize(nt);
    out.first_region.resize(nt + 1);
    out.region_block.reserve(choice.regions + 1);
    out.blocks.reserve(choice.blocks);
    for (size_t t = 0; t < nt; ++t) {
        TriangleLists &b = built[t][choice.layout];
        out.frames[t] = b.frame;
        out.first_region[t] =
            static_cast<uint32_t>(out.region_block.size()) << 2 | b.regions;
        const uint32_t first = static_cast<uint32_t>(out.blocks.size());
        for (uint32_t k = 0; k < b.regions * b.regions; ++k)
            out.region_block.push_back(first + (k ? b.end[k - 1] : 0));
        const uint32_t bent_offset = static_cast<uint32_t>(out.bent_windows.size());
        if (out.bent_windows.size() + b.bent_windows.size() >= bent_flag)
            throw std::length_error("closest-cell index: more than 2^31 bent windows");
        for (CellBlock &blk : b.blocks)
            for (uint32_t &c : blk.cell)
                if (c != ClosestCell::none && (c & bent_flag)) c += bent_offset;
        stats.bent_entries += b.bent_entries;
        out.bent_windows.insert(out.bent_windows.end(), b.bent_windows.begin(),
                                b.bent_windows.end());
        out.blocks.insert(out.blocks.end(), b.blocks.begin(), b.blocks.end());
        stats.triangles_without_cells_in_reach += b.entries == 0;
        stats.triangles_with_regions += b.regions > 1;
        stats.max_candidate_cells = std::max(stats.max_candidate_cells, b.longest);
        lists += b.regions * b.regions;
        entries += b.entries;
        distinct += b.distinct_triangles;
        built[t] = {};
    }
    out.first_region[nt] = static_cast<uint32_t>(out.region_block.size()) << 2 | 1;
    out.region_block.push_back(static_cast<uint32_t>(out.blocks.size()));
    stats.mean_candidates = lists ? double(distinct) / lists : 0;
    stats.mean_candidate_cells = lists ? double(entries) / lists : 0;
}

}  // namespace

ClosestCellIndex::ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                                   const ClosestCellOptions &options)
    : m_cells(&cells), m_options(options), m_lanes(lane_scanners(options.wide_lanes)) {
    m_stats.lanes = m_lanes.lanes;
    const auto t0 = std::chrono::steady_clock::now();
    const BuildScale scale = scale_of(crps, cells, m_options);
    m_spacing = scale.spacing;
    m_initial_radius = scale.initial_radius;
    m_max_radius = scale.max_radius;

    // Per triangle, in parallel; then concatenated in triangle order.
    BuiltLists built(crps.num_triangles());
    Candidates candidates;
    candidates.paths = m_options.neighbourhood == Neighbourhood::unfolding_teo
                           ? sim::UnfoldPaths::edges_and_vertices
                           : sim::UnfoldPaths::edges_only;
    if (m_options.neighbourhood != Neighbourhood::geodesic)
        build_unfolded(crps, scale, candidates, built);
    else
        build_geodesic(crps, scale, candidates, built, m_stats);

    const LayoutChoice choice = choose_layout(built, m_options.fine_regions_max_bytes);
    m_stats.fine_regions = choice.layout == 1;
    concatenate(built, choice,
                {m_frames, m_first_region, m_region_block, m_blocks, m_bent_windows},
                m_stats);
    m_stats.bytes = m_frames.size() * sizeof(TriangleFrame) +
                    m_first_region.size() * sizeof(uint32_t) +
                    m_region_block.size() * sizeof(uint32_t) +
                    m_blocks.size() * sizeof(CellBlock) +
                    m_bent_windows.size() * sizeof(BentWindow);
    m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace pelage::pattern::mosaic
