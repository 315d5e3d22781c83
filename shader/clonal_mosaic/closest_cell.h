// Closest-cell search by reverse neighbour mapping: H. J. Teo, M.Eng thesis, NTU 2006,
// ch. 6 (shared/seeds/001_…), §6.2 and Fig. 6.2.
//
// A surface point (t, q) — q in triangle t's local CRPS coordinates — is coloured by the
// cell nearest to it across the unfolded neighbourhood of t. Teo maps the *query* into
// each candidate triangle's frame (one rigid map per triangle) instead of mapping every
// cell into t's frame, visits triangles outward from t, and shrinks the search radius
// D_min whenever a closer cell turns up.
//
// What we precompute (Teo's method, kept, made fast). Each triangle t is split into n_t²
// sub-triangles S (regular subdivision in barycentric coordinates; n_t grows with the
// triangle's size in cell spacings, up to 3), and for each S:
//   * the candidate triangles: those of t's breadth-first unfolding (sim/unfold.h) that
//     hold cells and lie within R_S = d_3 + b_S of S (d_3: distance from S's centroid to
//     its third-nearest cell, b_S: S's bounding radius about that centroid). Every cell
//     that can be among the three nearest for some point q of S is within R_S of S:
//     F3(q) <= |q - c_3| <= d_3 + b_S.
//   * per candidate, the reverse map F[t→j] in float, the distance from S to j (a lower
//     bound for any query in S) and the radius of the circle about j's centroid that
//     holds j's cells;
//   * candidates sorted by that distance, so the loop stops at the first one farther
//     than the current D_min (Teo's adaptive radius, kept for the K-th nearest wanted).
// By default the unfolding walks edges only (sim/unfold.h, UnfoldPaths): the two
// triangles on either side of an edge then see identical maps for every triangle reached
// through that edge, which reduces Teo's "cracks" (§6.3); `pelage bench lookup` measures
// both.
//
// Thread-safety: immutable after construction; find() is const and allocation-free.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "shader/clonal_mosaic/cell_table.h"
#include "sim/crps.h"
#include "sim/unfold.h"

namespace pelage::shader {

struct Vec2f {
    float x = 0, y = 0;
};

struct ClosestCell {
    static constexpr uint32_t none = 0xffffffffu;
    uint32_t index = none;   // into the CellTable arrays; none when no cell is reachable
    uint32_t second = none;  // the second-nearest cell (find() and find_exhaustive() only)
    float f1 = std::numeric_limits<float>::infinity();  // distance to the nearest cell
    float f2 = std::numeric_limits<float>::infinity();  // ... to the second nearest
};

struct ClosestCellOptions {
    sim::UnfoldPaths paths = sim::UnfoldPaths::edges_only;
};

struct ClosestCellStats {
    double build_seconds = 0;
    double mean_candidates = 0;       // triangles per candidate list (per sub-triangle)
    double mean_candidate_cells = 0;  // cells held by those triangles
    size_t triangles_without_cells_in_reach = 0;
};

class ClosestCellIndex {
  public:
    ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                     const ClosestCellOptions &options = {});

    // Nearest cell (and F2) to point q (local CRPS coordinates) of triangle t, with Teo's
    // pruning, searching q's sub-triangle list.
    ClosestCell find(sim::TriId t, Vec2f q) const;
    // The nearest cell only (f2 left infinite): prunes harder, for hard-edged patterns.
    ClosestCell find_nearest(sim::TriId t, Vec2f q) const;

    // The K nearest cells, nearest first; missing entries are (none, +inf). Squared
    // distances: callers that blend take square roots of the ones they use.
    template <int K>
    struct Nearest {
        std::array<float, K> d2;
        std::array<uint32_t, K> index;
        Nearest() {
            d2.fill(std::numeric_limits<float>::infinity());
            index.fill(ClosestCell::none);
        }
    };
    // The three nearest: what a blend continuous across Voronoi vertices needs.
    Nearest<3> find_three(sim::TriId t, Vec2f q) const;
    // The candidates of every sub-triangle of t, without any pruning: the reference the
    // tests compare find() against (it checks the sub-triangle radii too).
    ClosestCell find_exhaustive(sim::TriId t, Vec2f q) const;

    // Distance from (t, q) to one cell through t's candidate map of the cell's triangle;
    // infinity when that triangle is not a candidate of t. For diagnostics (cracks).
    float distance_to_cell(sim::TriId t, Vec2f q, uint32_t cell) const;

    const ClosestCellStats &stats() const { return m_stats; }
    const CellTable &cells() const { return *m_cells; }

  private:
    struct Candidate {      // 32 bytes: two per cache line
        float c, s, ax, ay; // F[t→j]: the query into j's frame
        uint32_t begin, end;  // j's cells in the CellTable
        float reach;        // j's cells lie within `reach` of j's centroid
        float gap;          // distance from t to j in t's unfolding (lower bound)
    };
    static_assert(sizeof(Candidate) == 32);

    // Where q falls: v0 + [e1 e2] (b1, b2) = q, inverted per triangle; n = subdivision.
    struct TriangleRegions {  // 32 bytes
        float v0x, v0y, i00, i01, i10, i11;
        uint32_t n;
        uint32_t first_slot;  // slots (i * n + j) * 2 + upper, 2n² of them, some unused
    };
    static_assert(sizeof(TriangleRegions) == 32);
    struct Built;  // one triangle's regions while building

    uint32_t slot_of(sim::TriId t, Vec2f q) const;
    template <bool prune, int K>
    void scan(uint32_t slot, Vec2f q, Nearest<K> &n) const;
    void build_triangle(const sim::Crps &crps, sim::TriId t, sim::UnfoldScratch &scratch,
                        std::vector<sim::UnfoldedTriangle> &unfolded, Built &out) const;

    const CellTable *m_cells;
    ClosestCellOptions m_options;
    double m_initial_radius = 0, m_max_radius = 0, m_spacing = 0;
    std::vector<TriangleRegions> m_regions;
    std::vector<uint32_t> m_slot_row;  // candidates of slot s: [m_slot_row[s], m_slot_row[s + 1])
    std::vector<Candidate> m_candidates;
    std::vector<sim::TriId> m_candidate_tri;  // parallel to m_candidates; not in the hot loop
    ClosestCellStats m_stats;
};

}  // namespace pelage::shader
