// Closest-cell search by reverse neighbour mapping: H. J. Teo, M.Eng thesis, NTU 2006,
// ch. 6, §6.2 and Fig. 6.2.
//
// A surface point (t, q) — q in triangle t's local CRPS coordinates — is coloured by the
// cell nearest to it on the surface. Teo unfolds t's neighbourhood and maps the *query*
// into each candidate triangle's frame (one rigid map per triangle) instead of mapping
// every cell into t's frame, visits triangles outward from t, and shrinks the search
// radius D_min whenever a closer cell turns up.
//
// What is precomputed (Teo's method, made fast). Each triangle t is split into n²
// sub-triangles S (regular subdivision in barycentric coordinates; n grows with the
// triangle's size, about two per cell spacing across, up to 6). For each S, the cells'
// exact geodesic windows on t (sim/geodesic; see Neighbourhood below for the planar
// unfoldings kept to compare with) supply every cell that can be among the three nearest
// of some point of S: those within R_S of S, where R_S bounds F3 on S (at most d_3 + b_S,
// d_3 the distance from S's centroid to its third-nearest cell and b_S S's radius,
// because F3(q) <= |q - c_3| <= d_3 + b_S). Each such cell is stored *already placed in
// t's frame*, at the position that reproduces its surface distance over the region (see
// bent_flag, cell_block.h): the work Teo does per candidate triangle at every lookup is
// done once here, so a lookup is a scan of one flat list.
//
// Regions. The lists of neighbouring sub-triangles overlap heavily (the same cells at
// the same positions), so a lookup searches a *region* of t, whose list is the union of
// the lists of the S in it: fewer, shorter-in-total lists keep the index small enough
// to stay mostly in cache. Two layouts, one per index: *fine* regions, r = about one per
// cell spacing across t (at most 3 per side), when the whole index stays within
// ClosestCellOptions::fine_regions_max_bytes, else *coarse* ones: one region (t itself)
// for triangles up to six spacings across, r x r (r = 2, 3) beyond. Each list is sorted
// by its cells' distance from the region (a lower bound for every query in it) and
// packed five cells to a 64-byte block (float x[5], y[5], uint32 cell[5] and the block's
// squared bound: no padding bytes); the scan stops at the first block whose bound
// exceeds the current K-th nearest distance (Teo's adaptive radius D_min, for the K
// wanted). A triangle's blocks are contiguous; two small, cache-resident tables of
// uint32 offsets (per triangle its first region, per region its first block) locate a
// region's list from a hit's (b1, b2), so a random lookup is one cache miss on a
// contiguous run. (A search from a point q instead reads t's 32-byte frame for q's
// barycentric coordinates when r > 1.) The finer sub-triangles cost nothing at lookup
// and shorten the lists. Coarse regions trade longer scans (their bounds are taken
// from the whole triangle) for a smaller index; `pelage bench lookup` compares both.
// Positions stay float in t's frame: results are bit-identical to scanning the unfolding
// itself (a cell outside S's list is farther than F3 from all of S).
//
// The banded search for soft edges runs as a two-nearest scan (F2 lets
// coherent_lookup.h reuse the result for the next hits) followed by a pass over the
// same, by then cached, blocks for the cells within F1 + band (three_within()) —
// skipped when F2 lies beyond F1 + band, or when the bound on every other cell does.
//
// Two ways to scan a list. find() and find_nearest() serve hits in no useful order
// (indirect hits, `pelage lookup`), where which cell of a block is nearer is a coin
// toss and an insertion scan's branches mispredict: they keep each of a block's lanes'
// own K nearest in vector registers instead, selects only, and merge the lanes at the
// end (lane_scan.h; exact ties go to the insertion scan, which orders them by id). Four
// lanes with SSE2; eight with AVX2 (chosen at run time), which hold a whole block and
// select in one instruction. The banded search's first pass (its two nearest) runs lane
// by lane too when eight lanes are available; with four, it keeps the insertion scan,
// whose branches predict well on camera hits (they come in runs along one list). Its
// second pass, rare, always uses the insertion scan.
//
// With exact geodesics, the two triangles on either side of an edge agree on its points'
// nearest cells, so Teo's "cracks" (§6.3) vanish; `pelage bench lookup` measures them
// for every neighbourhood.
//
// Thread-safety: immutable after construction; find() is const and allocation-free.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "pattern/mosaic/cell_block.h"
#include "pattern/mosaic/cell_table.h"
#include "pattern/mosaic/lane_scan.h"
#include "sim/crps/crps.h"

namespace pelage::pattern::mosaic {

struct ClosestCell {
    static constexpr uint32_t none = 0xffffffffu;
    uint32_t index = none;  // into the CellTable arrays; none when no cell is reachable
    uint32_t second =
        none;  // the second-nearest cell (find() and find_exhaustive() only)
    float f1 = std::numeric_limits<float>::infinity();  // distance to the nearest cell
    float f2 = std::numeric_limits<float>::infinity();  // ... to the second nearest
};

// Where a triangle's candidate cells and their positions in its frame come from.
//   geodesic: exact polyhedral geodesics (sim/geodesic): each cell's windows on the
//     triangle; per region, the window that realises the cell's distance at most of the
//     region's sample points gives its position (a pseudo-source's σ folded in by moving
//     the source back by σ, away from the region).
//   unfolding_edges, unfolding_teo: the breadth-first planar unfolding of Teo 2006
//     §4.1 across edges only or across edges and vertices (sim/crps/unfold.h); kept to
//     measure against. They fold over around saddle vertices and thin parts.
enum class Neighbourhood { geodesic, unfolding_edges, unfolding_teo };

struct ClosestCellOptions {
    Neighbourhood neighbourhood = Neighbourhood::geodesic;
    // Regions searched per triangle side, at most (1 … 3): finer regions mean shorter
    // scans but longer lists in total (more memory, more cache misses on random
    // queries). Which triangles get more than one: see the layouts above.
    uint32_t max_subdivision = 3;
    // Fine regions (about one per cell spacing across) while the index stays within this
    // size, else one region per triangle up to six spacings across (see above).
    size_t fine_regions_max_bytes = 4'000'000;
    // Eight-lane AVX2 scans when the CPU has them (lane_scan.h); the results are the same
    // bits either way (false: the four-lane scans, for tests and benchmarks).
    bool wide_lanes = true;
};

struct ClosestCellStats {
    double build_seconds = 0;
    double mean_candidates = 0;       // distinct triangles per list (one per region)
    double mean_candidate_cells = 0;  // cells per list
    size_t max_candidate_cells = 0;   // in the longest list
    size_t bytes = 0;                 // frames + list offsets + blocks
    size_t triangles_without_cells_in_reach = 0;
    size_t triangles_with_regions = 0;  // searched in r x r regions (r > 1)
    bool fine_regions = false;          // which layout fitted (fine_regions_max_bytes)
    int lanes = 0;                      // the lane scans' width (lane_scan.h)
    // Neighbourhood::geodesic: the windows' final radius, the propagation rounds it
    // took, and the largest window set held at once (count, bytes).
    double geodesic_radius = 0;
    int geodesic_rounds = 0;
    size_t geodesic_windows = 0, geodesic_bytes = 0;
    size_t geodesic_work = 0;  // windows settled over all rounds, kept or not
    size_t bent_entries = 0;   // list entries of paths bent round a pseudo-source
};

class ClosestCellIndex {
  public:
    static constexpr uint32_t max_subdivision = 3;

    ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                     const ClosestCellOptions &options = {});

    // Nearest cell (and F2) to point q (local CRPS coordinates) of triangle t, with Teo's
    // pruning, searching t's list.
    ClosestCell find(sim::TriId t, Vec2f q) const;
    // The nearest cell only (f2 left infinite): prunes harder, for hard-edged patterns.
    ClosestCell find_nearest(sim::TriId t, Vec2f q) const;

    // The K nearest cells, nearest first; missing entries are (none, +inf). Squared
    // distances: callers that blend take square roots of the ones they use.
    template <int K>
    struct Nearest {
        std::array<float, K> d2;
        std::array<uint32_t, K> index;
        // The nearest cell's position in t's frame, exactly as its list stores it (so
        // d2[0] is recomputable bit for bit: a caller can reuse it for nearby queries).
        Vec2f nearest_at;
        // The second-nearest cell's position (as listed; +inf when there is none) —
        // find_three_within: also when it lies beyond the band and is not returned.
        Vec2f second_at{std::numeric_limits<float>::infinity(),
                        std::numeric_limits<float>::infinity()};
        uint32_t second = ClosestCell::none;  // find_three_within: that cell
        // A lower bound on the squared distance of every cell not among the K (the
        // scans and find_three: not necessarily F_{K+1}², only never above it).
        float beyond_d2 = std::numeric_limits<float>::infinity();
        // find_three_within only: the squared distance of the nearest cell it did not
        // return (F2² when it returned one cell; +inf when unknown), and a lower bound on
        // F3² (+inf when there is no third cell). With c2's position, a caller can prove
        // for a nearby query that no other cell comes near (coherent_lookup.h).
        float next_d2 = std::numeric_limits<float>::infinity();
        float third_d2 = std::numeric_limits<float>::infinity();
        // A returned cell's distance is not |q - its position| (a path bent round a
        // pseudo-source vertex, cell_block.h): nearby queries cannot reuse the result.
        bool bent = false;
        Nearest() {
            d2.fill(std::numeric_limits<float>::infinity());
            index.fill(ClosestCell::none);
        }
    };
    // The three nearest: what a blend continuous across Voronoi vertices needs.
    Nearest<3> find_three(sim::TriId t, Vec2f q) const;
    // The three nearest among the cells within F1 + band; the others are (none, +inf).
    // What a blend over a band of width `band` past the nearest cell needs, in one scan
    // that prunes at F1 + band instead of F3 (band = 0: the nearest cell and its ties).
    Nearest<3> find_three_within(sim::TriId t, Vec2f q, float band) const;
    // q's whole region list, without any pruning: the reference the tests compare find()
    // against (it checks the pruning bounds).
    ClosestCell find_exhaustive(sim::TriId t, Vec2f q) const;

    // The same searches from barycentric coordinates (b1, b2) of triangle t, the way the
    // renderer reports a hit: the point follows from t's frame (an independent read, so
    // it overlaps with the list's).
    ClosestCell find_nearest(sim::TriId t, float b1, float b2) const;
    Nearest<3> find_three_within(sim::TriId t, float b1, float b2, float band) const;
    // Local CRPS coordinates of barycentric point (b1, b2) of t (what those use).
    Vec2f point(sim::TriId t, float b1, float b2) const {
        return m_frames[t].point(b1, b2);
    }

    // Distance from (t, q) to one cell as t's unfolding places it; infinity when the cell
    // is not in t's list. For diagnostics (cracks).
    float distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const;

    // Whether every region of t lists a cell. False on a component of the surface that
    // holds no cell (a piece of a triangle soup smaller than the cells): every search on
    // t then returns none (pattern/transfer/cell_cover.h carries such triangles to the
    // closest cell-bearing surface).
    bool reaches_cells(sim::TriId t) const {
        const uint32_t first = m_first_region[t], r = first & 3u, g = first >> 2;
        for (uint32_t k = 0; k < r * r; ++k)
            if (m_region_block[g + k] == m_region_block[g + k + 1]) return false;
        return true;
    }

    const ClosestCellStats &stats() const { return m_stats; }
    // The mean cell spacing, sqrt(area / cells): the unit of the reach.
    double spacing() const { return m_spacing; }
    const CellTable &cells() const { return *m_cells; }

  private:
    // --- What the coherent path reads to reuse a search's result (coherent_lookup.h) ---
    friend class CoherentLookup;

    // The triangle in its frame (cell_block.h), for the barycentric coordinates of a
    // point (blocks_of()).
    const TriangleFrame &frame(sim::TriId t) const { return m_frames[t]; }
    // The regions per side of t's lists (1 … 3): a cell's listed position can differ
    // from one region of t to the next (geodesic neighbourhoods), so results are
    // comparable within one region only (coherent_lookup.h).
    uint32_t regions_per_side(sim::TriId t) const { return m_first_region[t] & 3u; }
    // The cell of a list entry (bent entries: cell_block.h, bent_flag).
    uint32_t cell_of(uint32_t entry) const {
        return entry == ClosestCell::none || !(entry & bent_flag)
                   ? entry
                   : m_bent_windows[entry & ~bent_flag].tag;
    }
    // A bent entry's exact distance from q. `listed`: the distance from the entry's
    // listed position (used between the windows).
    float bent_distance(uint32_t entry, Vec2f q, float listed) const;
    // Bent entries among the results: their cells and exact distances. The order stays
    // the one of the listed positions (the searches agree with one another; where a
    // bent cell's exact distance overtakes the next cell's, F1 may exceed F2).
    template <int K>
    void resolve(Nearest<K> &n, Vec2f q) const;
    // find_three_within() before resolve(): indices are list entries (bent_flag set for
    // bent ones), distances the listed positions'. For callers that reuse a result
    // (coherent_lookup.h): selection by listed positions, exact distances from resolve.
    Nearest<3> find_three_within_listed(sim::TriId t, float b1, float b2,
                                        float band) const;

    // --- The searches' internals (closest_cell.cpp) ---
    static constexpr int per_block = CellBlock::size;

    using Block = CellBlock;

    const Block *blocks_of(sim::TriId t, Vec2f q, const Block *&end) const;
    const Block *blocks_at(sim::TriId t, float b1, float b2, const Block *&end) const;
    Nearest<3> three_within(const Block *b, const Block *e, Vec2f q, float band) const;
    // Returns the first block not scanned (e when all were), having set n.beyond_d2 to
    // the least squared distance of the scanned cells it did not keep and that block's
    // bound; *cells_left_d2, when given, gets the former alone.
    template <bool prune, bool dedupe, int K>
    const Block *scan(const Block *b, const Block *e, Vec2f q, Nearest<K> &n,
                      float band = -1, float *cells_left_d2 = nullptr) const;
    // scan<true, false, K> for K = 1, 2 (find() and find_nearest(): hits in no useful
    // order), lane by lane without data-dependent branches (lane_scan.h); the same
    // results, bit for bit.
    template <int K>
    const Block *scan_lanes(const Block *b, const Block *e, Vec2f q, Nearest<K> &n,
                            float *cells_left_d2 = nullptr) const;

    // The index, as the build (closest_cell_build.cpp) assembles it from the
    // triangles' lists.
    const CellTable *m_cells;
    ClosestCellOptions m_options;
    double m_initial_radius = 0, m_max_radius = 0, m_spacing = 0;
    std::vector<TriangleFrame> m_frames;
    // t's regions are g, g + 1, … g + r² - 1 for g = m_first_region[t] >> 2; its low two
    // bits hold r, the regions per side. Region g's blocks are [m_region_block[g],
    // m_region_block[g + 1]). Neither needs t's frame: a hit's (b1, b2) picks the list
    // with reads of two small, cache-resident tables, so a random lookup waits on one
    // miss only, the list's (reading the frame first would add a second).
    std::vector<uint32_t> m_first_region;
    std::vector<uint32_t> m_region_block;
    std::vector<Block> m_blocks;
    std::vector<BentWindow> m_bent_windows;
    LaneScanners m_lanes;
    ClosestCellStats m_stats;
};

}  // namespace pelage::pattern::mosaic
