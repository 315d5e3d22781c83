// Closest-cell search by reverse neighbour mapping: H. J. Teo, M.Eng thesis, NTU 2006,
// ch. 6 (shared/seeds/001_…), §6.2 and Fig. 6.2.
//
// A surface point (t, q) — q in triangle t's local CRPS coordinates — is coloured by the
// cell nearest to it across the unfolded neighbourhood of t. Teo maps the *query* into
// each candidate triangle's frame (one rigid map per triangle) instead of mapping every
// cell into t's frame, visits triangles outward from t, and shrinks the search radius
// D_min whenever a closer cell turns up.
//
// What we precompute, once per triangle t (Teo's method, kept, made fast):
//   * the candidate triangles: those of t's breadth-first unfolding (sim/unfold.h) that
//     hold cells and lie within R_t of t, where R_t = d_2 + b_t (d_2: distance from t's
//     centroid to its second-nearest cell, b_t: t's bounding radius). Every cell that can
//     be the nearest or second-nearest for some point of t is within R_t of t.
//   * per candidate, the reverse map F[t→j] in float, the distance from t to j (a lower
//     bound for any query in t) and the radius of the circle about j's centroid that
//     holds j's cells.
//   * candidates sorted by that distance, so the loop stops at the first one farther
//     than the current D_min (Teo's adaptive radius).
// By default the unfolding walks edges only (sim/unfold.h, UnfoldPaths): the two
// triangles on either side of an edge then see identical maps for every triangle reached
// through that edge, which reduces Teo's "cracks" (§6.3); `pelage bench lookup` measures
// both.
//
// Thread-safety: immutable after construction; find() is const and allocation-free.
#pragma once

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
    uint32_t index = none;  // into the CellTable arrays; none when no cell is reachable
    float f1 = std::numeric_limits<float>::infinity();  // distance to the nearest cell
    float f2 = std::numeric_limits<float>::infinity();  // ... to the second nearest
};

struct ClosestCellOptions {
    sim::UnfoldPaths paths = sim::UnfoldPaths::edges_only;
};

struct ClosestCellStats {
    double build_seconds = 0;
    double mean_candidates = 0;       // triangles per candidate list
    double mean_candidate_cells = 0;  // cells held by those triangles
    size_t triangles_without_cells_in_reach = 0;
};

class ClosestCellIndex {
  public:
    ClosestCellIndex(const sim::Crps &crps, const CellTable &cells,
                     const ClosestCellOptions &options = {});

    // Nearest cell (and F2) to point q of triangle t, with Teo's pruning.
    ClosestCell find(sim::TriId t, Vec2f q) const { return search<true>(t, q); }
    // The same candidates without any pruning: the reference the tests compare against.
    ClosestCell find_exhaustive(sim::TriId t, Vec2f q) const { return search<false>(t, q); }

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

    template <bool prune>
    ClosestCell search(sim::TriId t, Vec2f q) const;
    void build_candidates(const sim::Crps &crps, sim::TriId t, sim::UnfoldScratch &scratch,
                          std::vector<sim::UnfoldedTriangle> &unfolded,
                          std::vector<Candidate> &out, std::vector<sim::TriId> &out_tri) const;

    const CellTable *m_cells;
    ClosestCellOptions m_options;
    double m_initial_radius = 0, m_max_radius = 0;
    std::vector<uint32_t> m_row;  // candidates of t: [m_row[t], m_row[t + 1])
    std::vector<Candidate> m_candidates;
    std::vector<sim::TriId> m_candidate_tri;  // parallel to m_candidates; not in the hot loop
    ClosestCellStats m_stats;
};

}  // namespace pelage::shader
