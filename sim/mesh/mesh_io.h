// Reading meshes from disk: OFF and PLY (our own parsers), OBJ (tinyobjloader) and,
// through assimp, glTF 2.0, FBX, Collada and the other formats assimp imports. Readers
// throw pelage::InputError naming the file (and the line or element where the format has
// one); they never return a half-read mesh.
#pragma once

#include <string>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct MeshReadStats {
    size_t polygons_triangulated = 0;  // faces with more than 3 corners, fanned
    // The names a file's objects can be selected by (OBJ `o` and `g` names; the nodes
    // and meshes of an assimp scene), in file order, and how many pieces were read: all
    // of them when no object is selected (OBJ groups, assimp mesh instances).
    std::vector<std::string> object_names;
    size_t pieces_read = 0;
    // Of those, the pieces skinned to bones: glTF 2.0 §3.7.3 places them by their joints
    // and ignores their node's transform, which the positions read here carry; the
    // renderer poses them (renderer/animation/rig.h).
    size_t skinned_pieces = 0;
};

// Dispatches on the extension (.off, .ply, .obj, or one assimp imports; any case).
// `object`, when not empty, selects the named object of the file (OBJ: the faces under
// `o NAME` or `g ... NAME ...`; assimp: the meshes under the node NAME, or the mesh
// NAME), and is an error, listing the names there are, when the file has none of that
// name. The mesh is returned as stored in the file: call clean_mesh()
// (sim/mesh/mesh_clean.h) before building topology.
TriangleMesh read_mesh(const std::string &path, MeshReadStats *stats = nullptr,
                       const std::string &object = "");

TriangleMesh read_off(const std::string &path, MeshReadStats *stats = nullptr);
// PLY, ASCII or binary (our own reader: assimp's crashes on damaged headers).
TriangleMesh read_ply(const std::string &path, MeshReadStats *stats = nullptr);
TriangleMesh read_obj(const std::string &path, MeshReadStats *stats = nullptr,
                      const std::string &object = "");
// glTF, FBX, Collada, ...: node transforms are baked into positions and normals,
// polygons triangulated; lengths are the file's own (glTF's metres, FBX's centimetres).
TriangleMesh read_assimp(const std::string &path, MeshReadStats *stats = nullptr,
                         const std::string &object = "");

// Whether read_mesh reads files with this extension (without the dot; any case).
bool is_mesh_extension(const std::string &ext);
// The extensions read_mesh reads, for messages: "off, obj, gltf, glb, fbx, ply, ...".
std::string mesh_extension_list();

}  // namespace pelage::sim
