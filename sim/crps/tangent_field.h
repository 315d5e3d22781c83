// The anisotropy direction A of Walter et al. SIGGRAPH 2001 §3.2.1 on a surface: one 2D
// vector per triangle, in that triangle's CRPS frame, whose length is |A|. The
// relaxation reads only this array, so any field (a constant world direction, or a
// painted or interpolated field) plugs in by filling it.
#pragma once

#include <array>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::sim {

struct TangentField {
    std::vector<Vec2d> a;  // per triangle; zero where the field is undefined
    bool empty() const { return a.empty(); }
};

// A constant world direction projected into each face (and rescaled to `magnitude`);
// faces perpendicular to it get a zero vector.
TangentField constant_world_field(const Crps &crps, std::array<double, 3> direction,
                                  double magnitude);

}  // namespace pelage::sim
