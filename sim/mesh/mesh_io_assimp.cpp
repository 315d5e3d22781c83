// Meshes in the formats assimp imports (glTF 2.0, FBX, Collada, 3DS, STL, ...; OFF, PLY
// and OBJ have readers of their own).
// assimp parses and triangulates; this file walks the node graph, bakes every node's
// global transform into positions and normals (a glTF scene places its meshes with node
// matrices), keeps the triangles of the selected object and checks what it keeps: no
// non-finite numbers, at least one triangle. Lengths are the file's own: glTF is in
// metres, FBX usually in centimetres; pelage converts nothing (an object's transform
// scales it). UVs keep assimp's convention, origin at the bottom left as in OBJ (its
// glTF importer flips glTF's v).
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <new>

#include "sim/core/input_error.h"
#include "sim/mesh/assimp_walk.h"
#include "sim/mesh/mesh_io.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::sim {
namespace {

using assimp_walk::Instance;
using assimp_walk::name_of;
using assimp_walk::SceneWalk;

// The file's materials, and for each of assimp's the index of ours (invalid_id for the
// unnamed or "DefaultMaterial" material assimp invents for meshes given none).
std::vector<MeshMaterial> read_materials(const aiScene &scene, const std::string &path,
                                         std::vector<uint32_t> *index) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::absolute(fs::path(path)).parent_path();
    std::vector<MeshMaterial> out;
    index->assign(scene.mNumMaterials, invalid_id);
    for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
        const aiMaterial &m = *scene.mMaterials[i];
        MeshMaterial mm;
        mm.name = name_of(m.GetName());
        if (mm.name.empty() || mm.name == AI_DEFAULT_MATERIAL_NAME) continue;
        (*index)[i] = static_cast<uint32_t>(out.size());
        aiColor4D c;
        if (m.Get(AI_MATKEY_BASE_COLOR, c) == aiReturn_SUCCESS ||
            m.Get(AI_MATKEY_COLOR_DIFFUSE, c) == aiReturn_SUCCESS)
            mm.diffuse = {double(c.r), double(c.g), double(c.b)};
        aiString tex;
        if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &tex) == aiReturn_SUCCESS ||
            m.GetTexture(aiTextureType_DIFFUSE, 0, &tex) == aiReturn_SUCCESS) {
            const std::string t = name_of(tex);
            // "*N" names a texture embedded in the file: no path to give.
            if (!t.empty() && t[0] != '*')
                mm.diffuse_texture =
                    fs::path(t).is_absolute()
                        ? t
                        : (dir / fs::path(t)).lexically_normal().string();
        }
        out.push_back(std::move(mm));
    }
    return out;
}

std::string count(size_t n, const char *one, const char *many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string no_triangles(size_t points, size_t lines) {
    return "holds no triangles" + (points + lines > 0
                                       ? " (only " + count(points, "point", "points") +
                                             " and " + count(lines, "line", "lines") + ")"
                                       : std::string());
}

// "holds no triangles (only ...)" when the file, read without assimp's validation, has
// points or lines and no triangles; "" otherwise. Only counts are looked at.
std::string points_and_lines_only(const std::string &path) {
    Assimp::Importer importer;
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
    const aiScene *scene = nullptr;
    try {
        scene = importer.ReadFile(path, 0);
    } catch (const std::exception &) {
        return "";
    }
    if (!scene || scene->mNumMeshes == 0) return "";
    size_t points = 0, lines = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh *mesh = scene->mMeshes[m];
        if (!mesh) return "";
        if (mesh->mNumFaces == 0) points += mesh->mNumVertices;
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const unsigned n = mesh->mFaces[f].mNumIndices;
            if (n >= 3) return "";
            (n == 2 ? lines : points) += 1;
        }
    }
    return no_triangles(points, lines);
}

}  // namespace

TriangleMesh read_assimp(const std::string &path, MeshReadStats *stats,
                         const std::string &object) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError(path, 0, "", "cannot open file");
    if (in.tellg() == 0) throw InputError(path, 0, "", "empty file");
    in.close();
    Assimp::Importer importer;
    assimp_walk::configure(importer);
    const unsigned flags = assimp_walk::import_flags;
    const aiScene *scene = nullptr;
    try {
        scene = importer.ReadFile(path, flags);
    } catch (const std::bad_alloc &) {
        throw InputError(path, 0, "", "out of memory while reading the file");
    } catch (const std::exception &e) {
        throw InputError(path, 0, "", std::string("cannot read the file: ") + e.what());
    }
    if (!scene) {
        std::string why = importer.GetErrorString();
        if (why.empty()) why = "unknown error";
        // Validation refuses a point cloud ("contains no faces"): say what it holds.
        const std::string only = points_and_lines_only(path);
        if (!only.empty()) throw InputError(path, 0, "", "the file " + only);
        // What assimp says when the extension's importer refuses the contents outright.
        if (why.rfind("No suitable reader found", 0) == 0) {
            const auto dot = path.find_last_of('.');
            why = "its contents are not a valid ." + path.substr(dot + 1) + " file";
        }
        throw InputError(path, 0, "", "cannot read the file: " + why);
    }
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode)
        throw InputError(path, 0, "", "the file holds no mesh (an incomplete scene)");

    const SceneWalk walk(*scene, object);
    if (!object.empty() && !walk.matched())
        fail_unknown_object(path, object, walk.names());

    // --- Which corner attributes every kept triangle has ---
    bool all_normals = true, all_uvs = true;
    size_t points = 0, lines = 0, triangles = 0;
    for (const Instance &in : walk.instances()) {
        const aiMesh &m = *scene->mMeshes[in.mesh];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
            (m.mPrimitiveTypes & aiPrimitiveType_LINE ? lines : points) += m.mNumFaces;
            continue;
        }
        triangles += m.mNumFaces;
        all_normals &= m.HasNormals();
        all_uvs &= m.HasTextureCoords(0);
    }
    const std::string what =
        object.empty() ? std::string("the file") : "object \"" + object + "\"";
    if (triangles == 0)
        throw InputError(path, 0, "", what + " " + no_triangles(points, lines));

    std::vector<uint32_t> material_index;
    TriangleMesh out;
    out.materials = read_materials(*scene, path, &material_index);
    bool any_material = false;

    // --- Each instance's triangles, transformed; faces numbered through the file ---
    std::vector<uint32_t> face_offset(scene->mNumMeshes + 1, 0);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
        face_offset[m + 1] = face_offset[m] + scene->mMeshes[m]->mNumFaces;
    size_t pieces = 0, skinned = 0;
    for (const Instance &in : walk.instances()) {
        const aiMesh &m = *scene->mMeshes[in.mesh];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        ++pieces;
        skinned += m.mNumBones > 0;
        const std::string mesh_label =
            "mesh " + std::to_string(in.mesh) +
            (m.mName.length > 0 ? " (\"" + name_of(m.mName) + "\")" : std::string());
        const double det = in.transform.determinant();
        if (!std::isfinite(det))
            throw InputError(path, 0, "",
                             mesh_label + ": its node transform is not finite");
        const VertId base = static_cast<VertId>(out.positions.size());
        for (unsigned v = 0; v < m.mNumVertices; ++v) {
            const Vec3d p = in.transform.point(m.mVertices[v]);
            if (!is_finite(p))
                throw InputError(path, 0, "",
                                 mesh_label + " vertex " + std::to_string(v) +
                                     ": non-finite position");
            out.positions.push_back(p);
        }
        const uint32_t material = m.mMaterialIndex < material_index.size()
                                      ? material_index[m.mMaterialIndex]
                                      : invalid_id;
        any_material |= material != invalid_id;
        // A mirroring transform turns the winding: swap two corners to keep it.
        const int order[3] = {0, det < 0 ? 2 : 1, det < 0 ? 1 : 2};
        for (unsigned f = 0; f < m.mNumFaces; ++f) {
            const aiFace &face = m.mFaces[f];
            if (face.mNumIndices != 3) continue;  // a stray point or line
            std::array<VertId, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                const unsigned idx = face.mIndices[order[k]];
                tri[k] = base + idx;
                if (all_normals) {
                    const Vec3d n = in.transform.normal(m.mNormals[idx]);
                    if (!is_finite(n))
                        throw InputError(path, 0, "",
                                         mesh_label + " vertex " + std::to_string(idx) +
                                             ": non-finite normal");
                    out.corner_normals.push_back(n);
                }
                if (all_uvs) {
                    const aiVector3D &uv = m.mTextureCoords[0][idx];
                    const Vec2d t{double(uv.x), double(uv.y)};
                    if (!std::isfinite(t.x) || !std::isfinite(t.y))
                        throw InputError(path, 0, "",
                                         mesh_label + " vertex " + std::to_string(idx) +
                                             ": non-finite texture coordinate");
                    out.corner_uvs.push_back(t);
                }
            }
            out.triangles.push_back(tri);
            out.source_face.push_back(face_offset[in.mesh] + f);
            out.triangle_material.push_back(material);
        }
    }
    if (!any_material) {
        out.materials.clear();
        out.triangle_material.clear();
    }
    if (stats) {
        stats->object_names = walk.names();
        stats->pieces_read = pieces;
        stats->skinned_pieces = skinned;
    }
    return out;
}

}  // namespace pelage::sim
