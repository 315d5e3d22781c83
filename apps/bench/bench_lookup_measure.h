// The measurements of `pelage bench lookup` (cmd_bench_lookup.cpp) on one surface with
// one neighbourhood: the search's time in each query order and mode, its agreement with
// the exhaustive search and with exact geodesics, and the crack rate along edges.
#pragma once

#include <ctime>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "pattern/mosaic/closest_cell.h"
#include "sim/crps/surface.h"
#include "sim/geodesic/windows_by_face.h"

namespace pelage::renderer::cli {

using LookupQuery = std::pair<sim::TriId, pattern::mosaic::Vec2f>;

// This thread's CPU seconds: on a shared machine wall time also counts the time other
// jobs hold the cores, CPU time only the lookups' own (cache contention still shows).
class CpuTimer {
  public:
    CpuTimer() : m_start(now()) {}
    double seconds() const { return now() - m_start; }

  private:
    static double now() {
        timespec ts{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
        return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    }
    double m_start;
};

// One run's JSON: the index built over `cells` with `neighbourhood` and `subdivision`,
// looked up at `queries` (random order) and `coherent` (the same, sorted by triangle),
// the first 20 000 queries compared with `exact`.
nlohmann::json measure_lookups(const sim::Surface &s,
                               const pattern::mosaic::CellTable &cells,
                               const std::vector<LookupQuery> &queries,
                               const std::vector<LookupQuery> &coherent,
                               pattern::mosaic::Neighbourhood neighbourhood,
                               uint32_t subdivision, const sim::WindowsByFace &exact);

}  // namespace pelage::renderer::cli
