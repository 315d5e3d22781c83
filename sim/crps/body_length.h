// The length of a body, for patterns whose scale is stated relative to the animal
// (SimParams::initial_spacing): the surface's extent along its principal axis, the
// dominant eigenvector of its area-weighted second moment about the centroid. It does not
// change with the mesh's orientation or with how finely it is tessellated, and for an
// animal it is its nose-to-tail (or, for a giraffe, hoof-to-head) length.
#pragma once

#include "sim/crps/crps.h"

namespace pelage::sim {

struct BodyAxis {
    Vec3d centroid, axis;  // unit axis
    double length = 0;     // extent of the triangles' corners along the axis
};

BodyAxis body_axis(const Crps &crps);

}  // namespace pelage::sim
