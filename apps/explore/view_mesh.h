// The mesh as the explorer's page draws it (explore.js, loadMesh): uint32 triangle count
// n, then n × 9 float32 positions, n × 9 float32 normals and n × 6 float32 texture
// coordinates, little-endian. The triangles are unwelded, since each has its own tile of
// the type texture (pattern_texture.h); the normals are averaged over the faces around
// each vertex, weighted by their areas, so the surface shades smoothly.
#pragma once

#include <cstdint>
#include <vector>

#include "apps/explore/pattern_texture.h"
#include "sim/mesh/mesh.h"

namespace pelage::renderer::explore {

std::vector<uint8_t> view_mesh_bytes(const sim::TriangleMesh &mesh,
                                     const TypeTextureLayout &layout);

}  // namespace pelage::renderer::explore
