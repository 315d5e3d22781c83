// One Jacobi relaxation step of the Clonal Mosaic on the CRPS (Walter 1998 Fig. 1 /
// thesis Fig. 3.2; Teo 2006 Fig. 5.3 for global, Fig. 5.6 for local relaxation):
//   D = unit(C − P)·(1 − d/r)·(1 − α[C][P])·r           for every neighbour P within r
//   C' = C + Σ (w_a·O + (1 − w_a)·w_d·D),   O = (D·Â)·A   (SG01 §3.2.1, A per triangle)
// All displacements are computed from the old positions, then every cell moves (Jacobi).
//
// Neighbour search (Teo §5.1.2): the cells of triangle t and of every triangle in t's
// unfolding within r. Distances go through the CRPS maps, never 3D: the cells of the
// unfolding are carried into t's frame through unfoldings checked against exact
// geodesics (neighbourhoods.h), so no force acts through a fold, and meet t's cells
// eight at a time in floats (pair_forces.h).
//
// Determinism: each triangle's forces are summed in a fixed order (triangle order of
// its unfolding, then bucket order, in fixed lanes) by one task; moves are applied
// serially in triangle order. Results do not depend on the number of threads or the
// CPU.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "sim/crps/tangent_field.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"
#include "sim/mosaic/neighbourhoods.h"
#include "sim/mosaic/pair_forces.h"

namespace pelage::sim {

struct RelaxContext {
    const Crps *crps = nullptr;
    const CellTypes *types = nullptr;
    const TangentField *field = nullptr;  // may be empty (no anisotropy)
    double r = 0, w_d = 0.1, w_a = 0;
    bool uniform_alpha = false;  // the initial phase: same α for every pair
    double alpha = 0;            // used when uniform_alpha
    uint64_t seed = 0;           // tie-break directions for coincident cells
    // Local parameters (sim/control), per cell id, or null for the constants above: the
    // moving cell's own radius (at most r, which the neighbourhoods cover), w_d, w_a
    // (at most w_a above) and anisotropy scale.
    const double *cell_r = nullptr, *cell_w_d = nullptr, *cell_w_a = nullptr,
                 *cell_a_scale = nullptr;
    // 1 − α felt by each cell from each type (max_cell_types per cell) where adhesion
    // varies by region; null: the types' matrix.
    const double *cell_one_minus_alpha = nullptr;
};

// A neighbour of a cell as the relaxation sees it.
struct RelaxNeighbour {
    CellId id;
    double distance;  // along the surface
    Vec2d away;       // C − P unfolded into C's frame (length = distance)
};

struct RelaxStepResult {
    double max_move = 0;     // largest displacement length, for convergence
    size_t cells_moved = 0;  // cells relaxed in this step (the cost measure)
};

class Relaxer {
  public:
    // One Jacobi step over the cells of `active` (sorted triangle ids). Cells of other
    // triangles push but do not move (Teo §5.1.3, Fig. 5.5(b)).
    RelaxStepResult step(const RelaxContext &ctx, Cells &cells,
                         const std::vector<TriId> &active);
    Neighbourhoods &neighbourhoods() { return m_nbhd; }
    // Over all steps so far: the wall time of the force sum, and the pairs of cells
    // within r it met (the work the relaxation cannot do without).
    double force_seconds() const { return m_force_seconds; }
    uint64_t interacting_pairs() const;
    // Every neighbour within r of cell c that pushes it, as step() would find them now
    // (for tests and tools; rebuilds the per-step state). Distances here are doubles;
    // step() decides d < r in floats, which can differ for a pair at r within 1e-7 r.
    std::vector<RelaxNeighbour> neighbours(const RelaxContext &ctx, const Cells &cells,
                                           CellId c);

  private:
    // 1 − α for every pair of types, resolved once per step.
    struct OneMinusAlpha {
        double m[max_cell_types][max_cell_types];
    };
    // One thread's copy of a triangle's cells and of its candidates as the force
    // kernel takes them (pair_forces.h).
    struct ForceScratch {
        std::vector<double> r;
        std::vector<float> target_x, target_z, target_r, target_oma, sum_x, sum_z;
        std::vector<uint8_t> coincident;
        std::vector<uint32_t> pairs;
        uint64_t pairs_total = 0;  // over the steps, for the statistics
        // The candidate chunks (pair_forces.h ForceCandidates), and each one's triangle.
        std::vector<uint32_t> first;
        std::vector<TriId> tri;
        std::vector<float> map_c, map_s, map_x, map_z, centre_x, centre_z, radius;
        void resize(size_t n) {
            r.resize(n);
            target_x.resize(n);
            target_z.resize(n);
            target_r.resize(n);
            target_oma.resize(n * max_cell_types);
            sum_x.resize(n);
            sum_z.resize(n);
            coincident.resize(n);
            pairs.resize(n);
        }
        uint32_t chunks = 0;  // candidate chunks listed, padding included
        void room_for_chunks(size_t n) {
            if (first.size() >= n) return;
            first.resize(n);
            tri.resize(n);
            for (auto *v :
                 {&map_c, &map_s, &map_x, &map_z, &centre_x, &centre_z, &radius})
                v->resize(n);
        }
    };

    void gather_by_triangle(const Cells &cells, size_t nt);
    void size_moves(const std::vector<TriId> &active);
    void accumulate_forces(const RelaxContext &ctx, const std::vector<TriId> &active);
    void push_triangle(const RelaxContext &ctx, TriId t, const OneMinusAlpha &oma,
                       ForceScratch &s, Vec2d *D) const;
    void list_candidate_chunks(TriId t, ForceScratch &s) const;
    Vec2d tie_break_pushes(const RelaxContext &ctx, const OneMinusAlpha &oma,
                           uint32_t row_k, const ForceScratch &s,
                           const ForceCandidates &candidates, const ForceTargets &targets,
                           uint32_t k) const;
    void bound_chunks(TriId t);
    const double *one_minus_alpha_row(const RelaxContext &ctx, const OneMinusAlpha &oma,
                                      uint32_t i) const;
    // Calls fn(p, away, d2) for every neighbour p (index in triangle order) of cell k of
    // triangle t within r; away is C − P in t's frame, d2 its squared length.
    template <typename Fn>
    void for_each_neighbour(TriId t, uint32_t k, double r, Fn &&fn) const;
    void walk_moves(const Crps &crps, const std::vector<TriId> &active);
    RelaxStepResult apply_moves(Cells &cells, const std::vector<TriId> &active) const;

    Neighbourhoods m_nbhd;
    // Cells copied into triangle order at the start of each step: the force loop then
    // reads contiguous memory instead of cells scattered by creation order.
    std::vector<uint32_t> m_row;
    std::vector<double> m_sx, m_sz;
    std::vector<uint8_t> m_st;
    std::vector<CellId> m_sid;
    // The same cells in floats, each triangle's padded to whole lanes (pair_forces.h).
    std::vector<uint32_t> m_padded_row;
    std::vector<float> m_fx, m_fz;
    std::vector<int32_t> m_ftype;
    std::vector<double> m_chunk_x, m_chunk_z;  // per chunk of eight, its circle
    std::vector<float> m_chunk_radius;
    tbb::enumerable_thread_specific<ForceScratch> m_force_scratch;
    double m_force_seconds = 0;
    std::vector<Vec2d> m_move;           // per active cell, in active order
    std::vector<uint32_t> m_active_row;  // offsets of each active triangle's cells
    std::vector<SurfacePoint> m_dest;
};

}  // namespace pelage::sim
