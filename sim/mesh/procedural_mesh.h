// Built-in meshes for tests and demos that need no download. All are closed and
// consistently wound (outward normals) unless stated otherwise.
#pragma once

#include <string>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

// Unit-radius UV sphere: `stacks` bands from pole to pole, `slices` around. Pole caps are
// triangle fans, so it has 2·slices·(stacks − 1) triangles: 20×20 gives Teo's 760.
TriangleMesh make_uv_sphere(int stacks, int slices, double radius = 1.0);
// Icosahedron subdivided `level` times, projected onto the sphere: 20·4^level triangles.
TriangleMesh make_icosphere(int level, double radius = 1.0);
// Torus about the Y axis: major radius R, minor radius r.
TriangleMesh make_torus(int major_segments, int minor_segments, double R, double r);
// Open square in the XZ plane, normal +Y, nx × nz quads split into triangles: a mesh with
// a boundary whose unfolding is the identity.
TriangleMesh make_plane(int nx, int nz, double size_x, double size_z);
// Open cylinder about the Y axis (no caps): developable, so unfolding is an isometry.
TriangleMesh make_cylinder(int around, int along, double radius, double height);

// Parses "sphere:20x20", "icosphere:3", "torus:48x24", "plane:10x10", "cylinder:32x8";
// throws InputError for a malformed spec. Used by `--mesh procedural:...` in the CLI.
TriangleMesh make_procedural(const std::string &spec);

}  // namespace pelage::sim
