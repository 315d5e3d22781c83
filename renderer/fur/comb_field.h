// Hair that follows the body: the comb direction of every skin triangle from a tangent
// field given as a preset's anisotropy field is (sim/field/field_spec.h: along or around
// the body's axis, a world direction, control vectors interpolated over the surface),
// or the field the object's pattern was grown with. The field is resolved on the
// object's rest mesh, whose triangles are the rendered ones, by the same code the
// simulation uses, so a zebra's hair lies along the field its stripes follow.
#pragma once

#include <string>
#include <vector>

#include "sim/crps/surface.h"
#include "sim/field/field_spec.h"

namespace pelage::renderer {

// 3 floats per triangle of `rest`: the field's unit direction in the rest mesh's space,
// zero where the field is undefined (a triangle perpendicular to a world direction).
std::vector<float> comb_by_triangle(const sim::FieldSpec &spec, const sim::Surface &rest);

// The anisotropy field of the preset a .cells file records. Throws pelage::InputError
// naming `cells_path` and `field` when the file has no preset or its preset no field.
sim::FieldSpec pattern_field(const std::string &cells_path, const std::string &field);

}  // namespace pelage::renderer
