// How much of a simulation run is done, for a progress bar. A step's cost grows about
// in proportion to the cell count (the relaxation, the divisions and the neighbourhood
// rebuilds all scale with it), and the count grows about exponentially, so a count of
// steps shows most of the bar early: the last tenth of the steps holds a large share
// of the work. The fraction here is the cells summed over the steps done over that
// sum plus an estimate of the rest: the count extrapolated at its recent growth rate
// (over the last eighth of the steps done; types that divide faster take over, so the
// rate rises) to the last step (end_time) or to target_cells, whichever comes first.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace pelage::sim {

class RunProgress {
  public:
    // `steps`: the run's relaxation steps (0 = open-ended, until `target_cells`);
    // `target_cells`: 0 = none.
    RunProgress(uint64_t steps, uint64_t target_cells, uint64_t initial_cells);

    // After step `step` (0-based) with `cells` cells: the fraction done, in [0, 1].
    double after_step(uint64_t step, uint64_t cells);

  private:
    uint64_t m_steps, m_target, m_initial;
    double m_done = 0;  // Σ cells over the steps done
    // (step, cells) every `m_stride` steps, thinned to stay small on long runs.
    std::vector<std::pair<uint64_t, uint64_t>> m_history;
    uint64_t m_stride = 1;
};

}  // namespace pelage::sim
