#include "sim/mosaic/run_progress.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {

RunProgress::RunProgress(uint64_t steps, uint64_t target_cells, uint64_t initial_cells)
    : m_steps(steps),
      m_target(target_cells),
      m_initial(std::max<uint64_t>(1, initial_cells)) {}

double RunProgress::after_step(uint64_t step, uint64_t cells) {
    const double m = double(std::max<uint64_t>(cells, 1));
    m_done += m;
    if (m_target > 0 && cells >= m_target) return 1.0;
    if (m_steps > 0 && step + 1 >= m_steps) return 1.0;
    if (step % m_stride == 0) {
        m_history.push_back({step, cells});
        if (m_history.size() >= 4096) {  // keep every other checkpoint
            size_t k = 0;
            for (size_t i = 0; i < m_history.size(); i += 2)
                m_history[k++] = m_history[i];
            m_history.resize(k);
            m_stride *= 2;
        }
    }
    // Growth per step over the last eighth of the steps (1 = none).
    const uint64_t window = std::max<uint64_t>(1, (step + 1) / 8);
    uint64_t from_step = 0, from_cells = m_initial;  // the count before step 0
    if (step + 1 > window) {
        const uint64_t want = step - window;
        auto it =
            std::upper_bound(m_history.begin(), m_history.end(), want,
                             [](uint64_t s, const std::pair<uint64_t, uint64_t> &h) {
                                 return s < h.first;
                             });
        if (it != m_history.begin()) {
            --it;
            from_step = it->first + 1;
            from_cells = std::max<uint64_t>(1, it->second);
        }
    }
    const double rate = std::max(
        1.0, std::pow(m / double(from_cells), 1.0 / double(step + 1 - from_step)));
    const double log_rate = std::log(rate);
    // Steps left: to end_time, or to the target at this rate, whichever is sooner.
    double left = m_steps > 0 ? double(m_steps - step - 1) : HUGE_VAL;
    if (m_target > 0 && log_rate > 1e-12)
        left = std::min(left, std::ceil(std::log(double(m_target) / m) / log_rate));
    if (!std::isfinite(left)) return 0.0;  // open-ended and nothing grows yet
    // Σ_{k=1..left} m rate^k, the count capped at the target.
    double rest;
    if (log_rate <= 1e-12) {
        rest = m * left;
    } else {
        const double cap = m_target > 0 ? double(m_target) : HUGE_VAL;
        const double uncapped = m * rate * std::expm1(left * log_rate) / (rate - 1);
        // Past the cap (rounding of `left`), the count stays at the target.
        const double k_cap = std::floor(std::log(cap / m) / log_rate);
        rest = k_cap >= left ? uncapped
                             : m * rate * std::expm1(k_cap * log_rate) / (rate - 1) +
                                   cap * (left - k_cap);
    }
    return std::clamp(m_done / (m_done + rest), 0.0, 1.0);
}

}  // namespace pelage::sim
