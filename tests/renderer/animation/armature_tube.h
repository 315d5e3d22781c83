// A skinned glTF laid out as Blender exports a Mixamo character (made in the tests,
// nothing third-party): an upright tube, radius 0.25, from y = 0 to y = 1.5, whose mesh
// node is a child of an "Armature" node with scale 0.01 and a −90° rotation about x.
// The tube's vertices are where its default pose puts them: each inverse bind matrix
// undoes its joint's global transform, the armature's included, so glTF 2.0 §3.7.3
// (a skinned mesh's node transform is ignored) shows it upright, 1.5 tall. Applying the
// mesh node's global transform instead (as sim::read_assimp does) lays it along −z at
// 1/100 of its size. Joints: "hips" at the base, "spine" at y = 0.75 (armature-local
// (0, 0, 75): centimetres, z up), the weights blending over 0.5 ≤ y ≤ 1; clip "Sway"
// (1 s) turns the spine 30° about x.
#pragma once

#include <string>

namespace pelage::test {

// The .gltf text (its buffer a data: URI): `around` × `along` quads, two triangles
// each, with outward normals.
std::string armature_tube(int around, int along);

// The tube's size in its default pose.
inline constexpr double armature_tube_radius = 0.25, armature_tube_height = 1.5;

}  // namespace pelage::test
