// A small skinned, morphing glTF made in the tests (nothing third-party): a strip 4
// long along x skinned to a root joint and a tip joint at x = 2 (weights blending over
// 1 ≤ x ≤ 3), a morph target lifting its end, and a rigid triangle (an "ear") on the tip
// joint. Clip "bend" (2 s): the tip turns 160° about z and back to 40°, the root slides,
// the morph weight goes 0 → 1; clip "still": one key, the rest; clip "roll" (1 s): the
// root turns 90° about x.
#pragma once

#include <string>

namespace pelage::test {

// The .gltf text (its buffer a data: URI). `weight_scale` multiplies every vertex's
// skin weights (1: valid).
std::string skinned_strip(double weight_scale = 1);

}  // namespace pelage::test
