// Hair that follows the body: the comb direction of every skin triangle from a tangent
// field given as a preset's anisotropy field is (sim/field/field_spec.h: along or around
// the body's axis, a world direction, control vectors interpolated over the surface),
// or the field the object's pattern was grown with. The field is resolved on the
// object's rest mesh, whose triangles are the rendered ones, by the same code the
// simulation uses, so a zebra's hair lies along the field its stripes follow.
#pragma once

#include <string>
#include <vector>

#include "renderer/core/math.h"
#include "sim/crps/surface.h"
#include "sim/field/field_spec.h"

namespace pelage::renderer {

// 9 floats per triangle of `rest` (3 per corner): the field's unit direction in the rest
// mesh's space at each corner, the area-weighted mean of the triangles around its
// vertex, so the comb is continuous across edges; zero where the field is undefined (a
// triangle perpendicular to a world direction) or cancels (a whorl).
// A field is an axis (the cells' anisotropy has no sense), hair has
// one: where the field lies within 60° of the line of `towards` (FurParams::comb_towards)
// it points along it, and elsewhere it keeps the sense of its neighbours. `smoothing`
// passes average each vertex's direction with its neighbours'
// (FurParams::comb_smoothing).
std::vector<float> comb_by_corner(const sim::FieldSpec &spec, const sim::Surface &rest,
                                  Vec3f towards, int smoothing);

// Carries `by_corner` (as comb_by_corner returns it, on the rest mesh) to a deformed pose
// of the same triangles: each corner's direction, in its triangle's plane, is written in
// the triangle's rest edges and rebuilt from its posed edges (the deformation gradient
// on the triangle), so the hair keeps its lie over the skin as the body bends, and a
// triangle's directions turn with it. `rest` has 3 doubles per vertex, `posed` 3 floats;
// directions stay unit length, zero ones and those of degenerate triangles zero.
void carry_to_pose(std::vector<float> &by_corner, const std::vector<uint32_t> &triangles,
                   const double *rest, const float *posed);

// The anisotropy field of the preset a .cells file was grown from, as the file records
// it (its params' "anisotropy_field", read by sim/field alone). Throws
// pelage::InputError naming `cells_path` and `field` when the file does not record it
// (an older pelage's) or its preset has no field.
sim::FieldSpec pattern_field(const std::string &cells_path, const std::string &field);

}  // namespace pelage::renderer
