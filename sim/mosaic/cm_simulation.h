// The Clonal Mosaic simulation on a mesh's CRPS: Walter, Fournier, Reimers, GI 1998 §3
// (event heap, Poisson division times, mutation, repulsion with adhesion), Walter's
// thesis ch. 6 (on polyhedral surfaces; Turk's area-uniform initial cells, §6.4) and
// Teo 2006 ch. 5 (Global and Local Relaxation, §5.1.2 and §5.1.4; cell walk, §5.2).
//
// Time: ρ relaxation steps per time unit. Step k covers (k/ρ, (k+1)/ρ]: every division
// due by (k+1)/ρ is executed in heap order (time, then cell id), then one relaxation
// step runs. The run stops at end_time, or once m reaches target_cells (when set), or
// when no division is left and end_time is 0.
//
// Local relaxation (Teo §5.1.4, second approach): a division marks the triangles within
// r of the *child* for S = local_steps steps; each step relaxes the cells of the marked
// triangles, with every cell within r (marked or not) pushing. Deviation from Teo, who
// marks the child's triangle and all of its neighbours: the disc of radius r around the
// child holds every cell the new cell pushes directly, and is much smaller than a
// triangle's neighbourhood when triangles are larger than r.
//
// Determinism: all random numbers are hashed from (seed, stream, counter) where the
// counter is a cell index or the division number; divisions run serially in heap order.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "sim/control/surface_control.h"
#include "sim/core/random.h"
#include "sim/crps/unfold.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"
#include "sim/mosaic/growing_surface.h"
#include "sim/mosaic/relaxation.h"

namespace pelage::sim {

struct SimStats {
    size_t initial_cells = 0;
    size_t initial_relax_steps = 0;
    size_t relax_steps = 0;  // relaxation events after initialisation
    size_t divisions = 0;
    uint64_t cell_steps = 0;  // Σ cells relaxed per step (initial phase included)
    double final_time = 0;
    double final_radius = 0;
    double seconds_initial = 0, seconds_total = 0;
    double seconds_neighbourhoods =
        0;  // building the unfolding cache (once per ~2× cells)
    size_t neighbourhood_builds = 0;
    double seconds_force_sum = 0;      // the relaxation's pair forces (pair_forces.h)
    uint64_t interacting_pairs = 0;    // pairs within r the force sum met, over all steps
    std::vector<GrowthSample> growth;  // one per reshape, and the end (growing runs)
    double growth_lost_cells = 0;  // ΔN no dividing cell was near (growing_surface.h)
};

// The initial count a run starts from: initial_cells, or initial_density × area, or the
// count whose hexagonal packing has initial_spacing × the body length. InputError above
// max_initial_cells.
inline constexpr double max_initial_cells = 1e8;
uint64_t initial_cell_count(const SimParams &params, const Crps &crps);

class CmSimulation {
  public:
    // The CRPS must outlive the simulation.
    CmSimulation(const Crps &crps, CellTypes types, SimParams params, uint64_t seed);

    // Regions, masks and local parameters resolved on this CRPS's surface
    // (sim/control/surface_control.h), before initialize(). With masks, a cell of a
    // masked type never stands where its mask is 0: not at initialisation, not as a
    // child, not after any relaxation step.
    void set_control(SurfaceControl control);
    const SurfaceControl &control() const { return m_control; }

    // Places the initial cells (count from params, or `override_cells` when > 0), draws
    // their types, relaxes them with one α for all pairs, schedules first divisions.
    void initialize(uint64_t override_cells = 0);
    // Runs to the end. `progress(fraction)` is called once per relaxation step with the
    // fraction of the work done (sim/mosaic/run_progress.h).
    void run(const std::function<void(double)> &progress = {});

    // Grows the surface while the simulation runs (Walter thesis §6.2, §6.8): the
    // simulation must have been built on surface->crps(). Every growth interval (rounded
    // to whole relaxation steps) the surface takes the shape at the current time, cells
    // keeping their barycentric points, and the divisions of the next interval come from
    // the growth of each triangle's area (growth_divisions) instead of the types'
    // division times, which then only give the relative rates. Divisions are drawn as a
    // Poisson process at each cell's rate (exponential waits, memoryless across
    // reshapes); a child divides from the next reshape on. The run ends at end_time, or
    // at the last key's age when end_time is 0; the surface ends in the shape of the
    // final time. The anisotropy field is resolved again on the surface's rest shape,
    // like the regions, and rides on the skin from there. Call before run().
    void set_growth(GrowingSurface *surface);
    // One relaxation step over `active` triangles (tests drive this directly).
    RelaxStepResult relax(const std::vector<TriId> &active, bool uniform_alpha);

    const Cells &cells() const { return m_cells; }
    Cells &cells() { return m_cells; }
    // The anisotropy vectors the relaxation reads, per triangle of the current shape.
    const TangentField &field() const { return m_field; }
    const SimStats &stats() const { return m_stats; }
    const CellTypes &types() const { return m_types; }
    const SimParams &params() const { return m_params; }
    double area() const { return m_area; }
    double radius() const;  // r = w_r·sqrt(A/m), Walter 1998 §3.3
    // The largest local radius anywhere (radius() without a local w_r).
    double max_radius() const;
    std::vector<size_t> count_by_type() const;

  private:
    struct Event {
        double time;
        CellId cell;
        bool operator>(const Event &o) const {
            return time > o.time || (time == o.time && cell > o.cell);
        }
    };
    // The time to a cell's next division; its mean may depend on where it is.
    double division_delay(int type, CounterRng &rng, SurfacePoint at) const;
    void schedule(CellId c, double time);
    // The masks' switch for cells that moved (Queiroz's switchCellType).
    void apply_masks_after_move(const std::vector<CellId> &moved);
    // Per-cell local relaxation parameters of the cells of `active`.
    void fill_local_parameters(const std::vector<TriId> &active, RelaxContext *ctx);
    // Takes the event by value: it pops the heap, which moves the front element.
    void divide(Event e);
    void grow(uint64_t update, double time);
    void surface_changed();
    // Resolves the anisotropy field with `p`: on the rest shape when growing (where
    // the regions are resolved), carried to the current shape.
    void build_field(const SimParams &p);
    void remember_field(const Crps &on);  // m_field (on `on`) in the edge bases
    void carry_field();                   // m_field from the edge bases on m_crps
    void mark_local(SurfacePoint at);
    std::vector<TriId> all_triangles_with_cells() const;
    std::vector<TriId> take_local_active();

    const Crps &m_crps;
    CellTypes m_types;
    SimParams m_params;
    uint64_t m_seed;
    double m_area = 0;
    TangentField m_field;
    SimParams m_field_params;                // what m_field is resolved with
    std::vector<Vec2d> m_field_edge_coords;  // m_field in each triangle's edge basis
    std::vector<double> m_field_length;
    Cells m_cells;
    Relaxer m_relaxer;
    SurfaceControl m_control;
    std::vector<double> m_cell_r, m_cell_w_d, m_cell_w_a, m_cell_a_scale;
    std::vector<double> m_cell_one_minus_alpha;  // max_cell_types per cell
    double m_now = 0;                            // simulated time of the current step
    uint64_t m_switches = 0;                     // cells the masks switched after a move
    std::vector<double> m_due;      // each cell's scheduled division (stale heap entries)
    std::vector<Event> m_heap;      // min-heap via std::push_heap with greater<>
    std::vector<int> m_steps_left;  // local relaxation: S countdown per triangle
    std::vector<TriId> m_marked;    // triangles with m_steps_left > 0
    SimStats m_stats;
    GrowingSurface *m_growth = nullptr;
    double m_cell_area = 0;    // a = A0 / N0 (thesis §6.2), at the first reshape
    double m_weight_mean = 0;  // W̄: the area-weighted mean local initial_weight, then
    std::vector<double> m_growth_mean;  // per cell: mean time between divisions now
};

}  // namespace pelage::sim
