// The closest-cell index's build (Teo 2006 §6.2; see closest_cell.h), shared by its three
// files and by nothing else: closest_cell_build.cpp assembles the index from the lists
// of every triangle, which closest_cell_lists.cpp builds one triangle at a time, from the
// candidate positions that closest_cell_candidates.cpp fits to the geodesic windows.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pattern/mosaic/cell_block.h"
#include "pattern/mosaic/cell_table.h"
#include "pattern/mosaic/closest_cell.h"
#include "sim/crps/crps.h"
#include "sim/crps/unfold.h"
#include "sim/geodesic/windows_by_face.h"

namespace pelage::pattern::mosaic::detail {

constexpr uint32_t max_regions =
    ClosestCellIndex::max_subdivision * ClosestCellIndex::max_subdivision;

// What a triangle's build reads of the index it builds.
struct BuildScale {
    const CellTable *cells = nullptr;
    uint32_t max_subdivision = ClosestCellIndex::max_subdivision;  // the options'
    // The mean cell spacing, the first guess of the reach, and the farthest any
    // unfolding reaches (the sum of all triangles' diameters).
    double spacing = 0, initial_radius = 0, max_radius = 0;
};

// Where a triangle's build finds its cells: the geodesic windows of every cell (grouped
// by triangle), or, for the unfolding neighbourhoods, per-thread unfolding state.
struct Candidates {
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
struct TriangleLists {
    TriangleFrame frame{};
    uint32_t regions = 1;  // sub-triangles per side searched at run time
    std::array<uint32_t, max_regions> end{};  // each list's, in blocks
    std::vector<CellBlock> blocks;
    std::vector<BentWindow> bent_windows;  // indexed by the blocks' bent entries, from 0
    size_t bent_entries = 0;
    size_t entries = 0, distinct_triangles = 0, longest = 0;
};

// A cell as a triangle's list sees it: its position in the triangle's frame.
struct Mapped {
    sim::Vec2d p;
    uint32_t cell;
    sim::TriId tri;  // the cell's own triangle (for statistics)
    // Not one straight line over the region (cell_block.h, bent_flag): the cell's
    // windows on the triangle, for its exact distance.
    bool bent = false;
    const sim::SourcedWindow *windows = nullptr;
    uint32_t num_windows = 0;
};

// closest_cell_candidates.cpp: the cells of t's windows `ws` that can be among the three
// nearest somewhere in `region`, appended to `list` at the positions that stand for
// their geodesic distances over it.
void map_region_candidates(std::span<const sim::SourcedWindow> ws,
                           const std::array<sim::Vec2d, 3> &region,
                           const std::vector<sim::TriId> &cell_tri,
                           std::vector<Mapped> &list);

// closest_cell_lists.cpp: t's lists in both layouts, out[0] coarse and out[1] fine.
// Returns the reach the lists needed (+inf when fewer than three cells were found): more
// than the geodesic radius means the windows were too short, and the lists are left
// unbuilt.
double build_triangle_lists(const sim::Crps &crps, sim::TriId t, const BuildScale &scale,
                            Candidates &candidates, std::array<TriangleLists, 2> &out);

}  // namespace pelage::pattern::mosaic::detail
