// The anisotropy vectors A of a run on a surface (SG01 §3.2.1; Queiroz & Walter §V.B for
// a field varying over the surface): the preset's field when it gives one
// (sim/field/field_spec.h), else its one world direction projected into every triangle.
// Empty when w_a = 0.
#pragma once

#include "sim/crps/tangent_field.h"
#include "sim/mosaic/cell_types.h"

namespace pelage::sim {

TangentField anisotropy_field(const SimParams &params, const Crps &crps);

}  // namespace pelage::sim
