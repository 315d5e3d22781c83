// The surface the explorer's preview stage grows on: the input simplified to the
// preview's larger cells (edges √divisor times the input's mean, so its triangles hold
// as many cells as the full run's do), kept within `deviation` of the bounding box's
// diagonal both ways (simplify.h's bound on the copy's vertices, and every input vertex
// near the copy: a thin part collapsed to a stub is refused), the edge halved while it
// is not. Nothing for meshes under 2 000 triangles (a preview on the input is quick
// enough) or over 200 000 (simplifying would take longer than the preview saves).
#pragma once

#include <optional>

#include "sim/mesh/mesh.h"

namespace pelage::renderer::explore {

std::optional<sim::TriangleMesh> simplify_for_preview(const sim::TriangleMesh &input,
                                                      double divisor, double deviation);

}  // namespace pelage::renderer::explore
