// One Jacobi relaxation step of the Clonal Mosaic on the CRPS (Walter 1998 Fig. 1 /
// thesis Fig. 3.2; Teo 2006 Fig. 5.3 for global, Fig. 5.6 for local relaxation):
//   D = unit(C − P)·(1 − d/r)·(1 − α[C][P])·r           for every neighbour P within r
//   C' = C + Σ (w_a·O + (1 − w_a)·w_d·D),   O = (D·Â)·A   (SG01 §3.2.1, A per triangle)
// All displacements are computed from the old positions, then every cell moves (Jacobi).
//
// Neighbour search (Teo §5.1.2): the cells of triangle t and of every triangle in t's
// unfolding within r. Distances go through the CRPS maps, never 3D: the query cell is
// carried into the neighbour's frame (reverse mapping, Teo §6.2), through unfoldings
// checked against exact geodesics (Neighbourhoods), so no force acts through a fold.
//
// Determinism: each triangle's forces are summed in a fixed order (triangle order of
// its unfolding, then bucket order) by one task; moves are applied serially in triangle
// order. Results do not depend on the number of threads.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <vector>

#include "sim/crps/tangent_field.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"
#include "sim/mosaic/pair_forces.h"

namespace pelage::sim {

// Unfoldings within a radius R ≥ r, built once and kept per triangle: r only shrinks as
// cells are added, so when r < R / (slack · filter_ratio) the entries farther than the
// new R are dropped (keeping the candidate set tight without unfolding again); the cache
// is built anew only when r > R (it would miss triangles) or the surface changes shape.
//
// The unfolding walks across edges only, so every map is the unfolding of an edge path
// (Teo's vertex maps rotate about a line, not along the surface). Around a vertex whose
// angles do not sum to 2π (a cone or a saddle: horns, ears, leg tops) paths on either
// side unfold a triangle to different places, and a planar unfolding overlaps itself
// or gapes: there a straight segment between two images is no path on the surface, and
// a triangle from elsewhere on the body can land near the master (the folds). A
// triangle reached from a first image that lands it elsewhere gets another image (up to
// max_images, those more than image_tolerance·R/2 apart). Unless every path agrees and
// no boundary is within reach (the unfolding is then the surface laid flat), each
// triangle's images are checked against exact geodesic distances from the master's
// centroid (sim/geodesic, Chen & Han window propagation) at the triangle's corners,
// edge midpoints and centroid: the image that agrees best is kept if it agrees within
// image_tolerance·R, and a triangle with no such image, or none within R along the
// surface, is dropped (validation.md, the relaxation's neighbours).
class Neighbourhoods {
  public:
    struct Entry {
        TriId tri;
        // The smallest R this entry belongs to: the distance from t to j in the
        // unfolding, and the image's disagreement with exact geodesics over
        // image_tolerance.
        float needs;
        RigidMap2 to_nbr;  // F[t→j]: carries a point of t into j's frame
    };
    static constexpr double slack = 1.15, filter_ratio = 1.1;
    static constexpr int max_images = 3;
    static constexpr double image_tolerance = 0.05;

    // Whether images are checked against exact geodesics (the default; off, the first
    // image of the breadth-first unfolding stands, as in Teo 2006 §4.1).
    void set_verified(bool verified) { m_verified = verified; }
    // Makes sure the cache covers radius r.
    void update(const Crps &crps, double r);
    // Forgets the cache: the next update rebuilds it (the surface changed shape).
    void invalidate() { m_radius = 0; }
    const std::vector<Entry> &of(TriId t) const { return m_entries[t]; }
    // Radius of t's bounding circle about its centroid (the origin of its 2D frame).
    double bounding_radius(TriId t) const { return m_bounding[t]; }
    double radius() const { return m_radius; }
    size_t rebuilds() const { return m_rebuilds; }
    size_t filters() const { return m_filters; }
    double seconds() const { return m_seconds; }  // total time spent building
    // The entries over all triangles, and the memory they take.
    size_t entries() const;
    size_t bytes() const;

  private:
    void filter(double R);

    std::vector<std::vector<Entry>> m_entries;
    std::vector<double> m_bounding;
    double m_radius = 0;
    size_t m_rebuilds = 0, m_filters = 0;
    double m_seconds = 0;
    bool m_verified = true;
};

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
        std::vector<float> x, z, centre_x, centre_z, radius;
        std::vector<int32_t> type;
        std::vector<uint32_t> row;  // the candidate's row in triangle order, or none
        size_t cells = 0;           // candidates written, padding included
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
        // Room for `chunks` chunks; chunks past the candidates' are never read as cells.
        void resize_candidates(size_t chunks) {
            const size_t cells = chunks * force_lanes;
            if (x.size() < cells) {
                x.resize(cells);
                z.resize(cells);
                type.resize(cells);
                row.resize(cells);
            }
            centre_x.resize(chunks);
            centre_z.resize(chunks);
            radius.resize(chunks);
        }
    };

    void gather_by_triangle(const Cells &cells, size_t nt);
    void size_moves(const std::vector<TriId> &active);
    void accumulate_forces(const RelaxContext &ctx, const std::vector<TriId> &active);
    void push_triangle(const RelaxContext &ctx, TriId t, const OneMinusAlpha &oma,
                       ForceScratch &s, Vec2d *D) const;
    uint32_t gather_candidates(TriId t, ForceScratch &s) const;
    Vec2d tie_break_pushes(const RelaxContext &ctx, const OneMinusAlpha &oma,
                           uint32_t row_k, const ForceScratch &s,
                           const ForceTargets &targets, uint32_t k) const;
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
