// Cell types of the Clonal Mosaic model and the parameters of a run (the presets that
// set them are read by preset.h).
// Walter, Fournier, Reimers, GI 1998, Table 1 ("Attributes of a cell") and Walter's
// thesis (UBC 1998) §3.3; Teo (NTU 2006) Table 3.1, whose "repulsiveness" is 1 − α.
//
// Conventions used throughout the simulation:
//   * division_time is the *mean time between divisions* (Walter's "division rate",
//     Table 1); +inf means the type never divides.
//   * mutation[p][c] is the probability that a child of a type-p parent is of type c
//     (row = parent); every row sums to 1.
//   * alpha[c][p] is the adhesion felt by a moving cell of type c from a neighbour of
//     type p (row = moving cell): the displacement scales with 1 − alpha[c][p].
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sim/field/field_spec.h"

namespace pelage::sim {

inline constexpr int max_cell_types = 8;

struct CellType {
    std::string name;
    std::array<float, 3> colour{0.5f, 0.5f, 0.5f};  // linear RGB
    float eumelanin = 0, pheomelanin = 0;           // for the fur shader
    double division_time = std::numeric_limits<double>::infinity();
    double initial_probability = 0;
    bool divides() const {
        return division_time < std::numeric_limits<double>::infinity();
    }
};

class CellTypes {
  public:
    CellTypes() = default;
    // Checks sizes only; value ranges are checked by the preset parser.
    CellTypes(std::vector<CellType> types, std::vector<std::vector<double>> mutation,
              std::vector<std::vector<double>> alpha);

    int size() const { return static_cast<int>(m_types.size()); }
    const CellType &operator[](int i) const { return m_types[i]; }
    const std::vector<CellType> &types() const { return m_types; }
    double mutation(int parent, int child) const { return m_mutation[parent][child]; }
    double alpha(int c, int p) const { return 1.0 - m_one_minus_alpha[c][p]; }
    // 1 − α[c][p], the factor the hot loop needs (Walter 1998 Fig. 1, step 1(c)).
    double one_minus_alpha(int c, int p) const { return m_one_minus_alpha[c][p]; }

    // The type a child of `parent` gets for a uniform number u in [0, 1).
    int mutate(int parent, double u) const;

    // "F" (foreground) and "B" (background) by name, else types 0 and 1; −1 if absent.
    int foreground() const;
    int background() const;
    int find(const std::string &name) const;  // −1 if absent

  private:
    std::vector<CellType> m_types;
    std::array<std::array<double, max_cell_types>, max_cell_types> m_mutation{};
    std::array<std::array<double, max_cell_types>, max_cell_types> m_one_minus_alpha{};
};

enum class RelaxMode { local, global };
enum class DivisionDistribution { poisson, exponential };

// Every number that drives a run, with the paper symbol it stands for.
struct SimParams {
    // --- Initial cells (Walter thesis §6.4: Turk's area-uniform sampling) ---
    uint64_t initial_cells = 0;  // used when > 0
    double initial_density = 0;  // cells per unit area, used when initial_cells == 0
    // The pattern's scale relative to the body: the distance between neighbouring
    // initial cells as a fraction of the body's length (sim/crps/body_length.h), so a
    // preset gives the same pattern on any body whatever its units or tessellation.
    // Used when initial_cells and initial_density are 0: m = 2A / (sqrt(3) (s L)^2), the
    // count whose hexagonal packing has that spacing.
    double initial_spacing = 0;
    int initial_relax_steps = 50;           // cap of the initial relaxation phase
    double initial_relax_alpha = 0.0;       // same α for every pair during that phase
    double initial_relax_tolerance = 0.01;  // stop when max displacement < tol · r

    // --- Relaxation (Walter 1998 Fig. 1; SG01 §3.2.1 anisotropy) ---
    double w_r = 2.0;                                     // r = w_r · sqrt(A / m)
    double w_d = 0.1;                                     // displacement weight
    double w_a = 0.0;                                     // anisotropy weight in [0, 1]
    std::array<double, 3> anisotropy_direction{0, 1, 0};  // world direction of A
    double anisotropy_magnitude = 0;                      // |A|
    // A per-triangle direction of A instead of the one world direction
    // (sim/field/field_spec.h; resolved on the surface by anisotropy_field.h).
    FieldSpec anisotropy_field;
    RelaxMode relax = RelaxMode::local;
    int local_steps = 4;  // S of Teo §5.1.4

    // --- Time (Walter 1998 §3.4: event heap, ρ relaxation steps per time unit) ---
    double rho = 18;
    double end_time = 0;
    uint64_t target_cells = 0;  // stop once m reaches it (0 = no target)
    DivisionDistribution division_distribution = DivisionDistribution::poisson;
    double child_radius_factor = 0.005;  // child within 0.005·r (a disc of diameter 1% r)
};

}  // namespace pelage::sim
