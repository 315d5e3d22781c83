// One textured mesh as a binary glTF 2.0 file (.glb; Khronos glTF 2.0 specification,
// section 4.4 "GLB File Format Specification"): a JSON chunk and a binary chunk holding
// the vertices (POSITION, NORMAL, TEXCOORD_0), the triangles (UNSIGNED_INT indices) and
// the texture (PNG), with one material whose baseColorTexture is the texture. Written
// directly rather than through assimp's exporter, which would rebuild the mesh from its
// own scene structure and choose its own material and sampler fields.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pelage::renderer {

struct GlbMesh {
    std::string name;
    // Per vertex: xyz, unit xyz (or empty), uv in glTF's convention (v down from the
    // image's top row).
    std::vector<float> positions, normals, uvs;
    std::vector<uint32_t> indices;  // 3 per triangle
};

// Welds triangle corners that share a vertex, a UV and a normal into one glTF vertex.
// `corner_uvs` are in OBJ's convention (v up), 2 per corner; `corner_normals` 3 per
// corner or empty (area-weighted vertex normals are then made).
GlbMesh glb_mesh(const std::string &name, const std::vector<double> &positions,
                 const std::vector<uint32_t> &triangles,
                 const std::vector<float> &corner_normals,
                 const std::vector<float> &corner_uvs);

// Writes `mesh` textured by `png` (a PNG file's bytes) to `path` atomically. Throws
// std::runtime_error naming the path when it cannot be written.
void write_glb(const std::string &path, const GlbMesh &mesh, const std::string &png,
               const std::string &generator);

}  // namespace pelage::renderer
