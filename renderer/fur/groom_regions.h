// The fur's regions (FurParams::regions, a preset's "regions" format) on the skin: each
// region's weight at every triangle corner, resolved on the object's rest surface by the
// code that resolves a preset's (sim/control/surface_control.h), so a height or `near`
// region means on the fur what it means in a preset.
#pragma once

#include <string>
#include <vector>

#include "sim/control/control_spec.h"
#include "sim/crps/surface.h"

namespace pelage::renderer {

// spec.region_names.size() floats per triangle corner, 3 corners per triangle (the
// layout SkinMesh::region_corners reads). Texture regions read the surface's UVs,
// relative paths resolved against `scene_path`'s folder; an InputError names
// `scene_path` and `field` + ".regions.NAME" when a region cannot be resolved.
std::vector<float> region_corners(const sim::ControlSpec &spec, const sim::Surface &rest,
                                  const std::string &scene_path,
                                  const std::string &field);

}  // namespace pelage::renderer
