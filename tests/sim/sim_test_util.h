// Small helpers shared by the simulation tests: a preset written in code and
// nearest-neighbour spacing statistics.
#pragma once

#include <string>

#include "sim/crps/crps.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cells.h"

namespace pelage::test {

// A one- or two-type preset in JSON, with the simulation block given verbatim.
inline std::string preset_json(const std::string &simulation, bool two_types = false,
                               const std::string &division_time = "\"never\"") {
    std::string types = R"({"name": "F", "colour": [0.1, 0.1, 0.1], "division_time": )" +
                        division_time + R"(, "initial_probability": )" +
                        (two_types ? "0.5" : "1.0") + "}";
    std::string adhesion = "[[0.0]]";
    if (two_types) {
        types +=
            R"(, {"name": "B", "colour": [0.9, 0.7, 0.3], "division_time": "never", "initial_probability": 0.5})";
        adhesion = "[[0.8, 0.0], [0.0, 0.4]]";
    }
    return R"({"name": "test", "types": [)" + types + R"(], "adhesion": )" + adhesion +
           R"(, "simulation": )" + simulation + "}";
}

// A region's documented profile (docs/guide/growth-and-control.md): 1 up to the limit,
// smoothstep down to 0 over `blend` beyond, written out independently of sim/control.
inline double expected_profile(double over, double blend) {
    if (over <= 0) return 1;
    if (over >= blend) return 0;
    const double x = over / blend;
    return 1 - (3 * x * x - 2 * x * x * x);
}

// Coefficient of variation of the nearest-neighbour distance (3D; fine for measuring
// spacing on a smooth closed surface where neighbours are close).
double nearest_neighbour_cv(const sim::Crps &crps, const sim::Cells &cells);

}  // namespace pelage::test
