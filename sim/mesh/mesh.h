// A triangle mesh as pelage sees it: indexed positions plus optional per-corner normals
// and UVs (OBJ stores them with their own indices, so they stay per corner), and the
// materials the file assigns to its triangles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/check.h"
#include "sim/core/vec.h"

namespace pelage::sim {

using TriId = uint32_t;
using VertId = uint32_t;
inline constexpr uint32_t invalid_id = 0xffffffffu;

struct Bounds3 {
    Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    void extend(Vec3d p);
    double diagonal() const;  // 0 for an empty box
};

// A material as the mesh file defines it (OBJ's .mtl, a glTF/FBX/... material): only
// what a diffuse surface needs.
struct MeshMaterial {
    std::string name;
    Vec3d diffuse{0.8, 0.8, 0.8};  // Kd, or glTF's baseColorFactor; linear RGB
    // map_Kd (resolved against the .mtl's folder), or the base colour texture (against
    // the mesh file's folder); "" = none, or a texture embedded in the file.
    std::string diffuse_texture;
};

struct TriangleMesh {
    std::vector<Vec3d> positions;
    std::vector<std::array<VertId, 3>> triangles;
    // Either empty or 3 entries per triangle (corner order follows `triangles`).
    std::vector<Vec3d> corner_normals;
    std::vector<Vec2d> corner_uvs;
    // For each triangle, the face of the source file it came from (polygons are fanned,
    // degenerate triangles dropped), so errors and tools can point back at the file.
    std::vector<uint32_t> source_face;
    // The file's materials, and for each triangle the index of its own (invalid_id: the
    // file gives it none). triangle_material is empty when the file has no materials.
    std::vector<MeshMaterial> materials;
    std::vector<uint32_t> triangle_material;
    // Other per-vertex scalars of the file by name (a PLY vertex's extra properties),
    // each with one value per entry of `positions`; empty for formats without them.
    std::vector<std::pair<std::string, std::vector<float>>> vertex_attributes;

    size_t num_triangles() const { return triangles.size(); }
    size_t num_vertices() const { return positions.size(); }
    Vec3d vertex(TriId t, int corner) const {
        PELAGE_DCHECK(t < triangles.size() && corner >= 0 && corner < 3);
        PELAGE_DCHECK(triangles[t][corner] < positions.size());
        return positions[triangles[t][corner]];
    }
    Vec3d face_normal_unnormalized(TriId t) const;  // (v1 - v0) x (v2 - v0)
    double triangle_area(TriId t) const;
    Bounds3 bounds() const;
    double surface_area() const;
};

}  // namespace pelage::sim
