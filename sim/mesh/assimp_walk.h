// The walk over an assimp scene's node graph that decides which meshes a mesh reference
// reads and in what order, with each one's global transform. read_assimp() numbers its
// vertices in this order (each instance's mesh vertices in turn), and a rig read from the
// same file (renderer/animation) uses the same walk, so both agree vertex for vertex.
#pragma once

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <string>
#include <vector>

#include "sim/mesh/mesh.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::sim::assimp_walk {

// How every reader of a file through assimp imports it, so that they see the same
// meshes and vertices: polygons triangulated, points and lines split off, no stick
// figure drawn for a skeleton without a mesh.
inline constexpr unsigned import_flags =
    aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
inline void configure(Assimp::Importer &importer) {
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
}

// A node's global transform in double precision: 3x3 linear part and translation.
struct Transform {
    double a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double t[3] = {0, 0, 0};

    static Transform from(const aiMatrix4x4 &m) {
        Transform x;
        const ai_real *r[3] = {m[0], m[1], m[2]};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) x.a[i][j] = double(r[i][j]);
            x.t[i] = double(r[i][3]);
        }
        return x;
    }
    Transform operator*(const Transform &o) const {
        Transform x;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                x.a[i][j] = 0;
                for (int k = 0; k < 3; ++k) x.a[i][j] += a[i][k] * o.a[k][j];
            }
            x.t[i] = t[i];
            for (int k = 0; k < 3; ++k) x.t[i] += a[i][k] * o.t[k];
        }
        return x;
    }
    double determinant() const {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
               a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
    Vec3d point(const aiVector3D &p) const {
        const double v[3] = {double(p.x), double(p.y), double(p.z)};
        double r[3];
        for (int i = 0; i < 3; ++i)
            r[i] = a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2] + t[i];
        return {r[0], r[1], r[2]};
    }
    // Normals transform by the inverse transpose, here the cofactor matrix (det · A^-T)
    // with the determinant's sign: a mirror keeps normals on the side they were.
    Vec3d normal(const aiVector3D &n) const {
        const double v[3] = {double(n.x), double(n.y), double(n.z)};
        const double s = determinant() < 0 ? -1.0 : 1.0;
        double r[3];
        for (int i = 0; i < 3; ++i) {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            double sum = 0;
            for (int j = 0; j < 3; ++j) {
                const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                sum += (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) * v[j];
            }
            r[i] = s * sum;
        }
        const Vec3d n_world{r[0], r[1], r[2]};
        const double len = length(n_world);
        return len > 0 ? n_world / len : n_world;
    }
};

inline std::string name_of(const aiString &s) { return std::string(s.C_Str()); }

// One mesh placed by one node.
struct Instance {
    unsigned mesh;
    Transform transform;
    const aiNode *node;  // the node that places it
};

class SceneWalk {
  public:
    // Walks the whole scene; `object` ("" = everything) selects a node or a mesh.
    SceneWalk(const aiScene &scene, const std::string &object)
        : m_scene(scene), m_object(object) {
        walk(*scene.mRootNode, Transform{}, object.empty());
    }
    const std::vector<Instance> &instances() const { return m_instances; }
    // Nodes that hold a mesh in their subtree, and meshes, each name once.
    std::vector<std::string> names() const { return unique_names(m_names); }
    bool matched() const { return m_matched; }

  private:
    // Whether the subtree holds a mesh; `take` when the subtree is selected.
    bool walk(const aiNode &node, const Transform &parent, bool take) {
        const Transform global = parent * Transform::from(node.mTransformation);
        const std::string name = name_of(node.mName);
        if (!m_object.empty() && name == m_object) {
            m_matched = true;
            take = true;
        }
        // The node's name goes before its meshes' and its children's (file order); it
        // is filled in once the subtree is known to hold a mesh.
        const size_t slot = m_names.size();
        m_names.emplace_back();
        bool has_mesh = node.mNumMeshes > 0;
        for (unsigned i = 0; i < node.mNumMeshes; ++i) {
            const unsigned m = node.mMeshes[i];
            if (m >= m_scene.mNumMeshes) continue;  // assimp's validation forbids it
            const std::string mesh_name = name_of(m_scene.mMeshes[m]->mName);
            m_names.push_back(mesh_name);
            const bool named = !m_object.empty() && mesh_name == m_object;
            m_matched |= named;
            if (take || named) m_instances.push_back({m, global, &node});
        }
        for (unsigned c = 0; c < node.mNumChildren; ++c)
            has_mesh |= walk(*node.mChildren[c], global, take);
        if (has_mesh) m_names[slot] = name;
        return has_mesh;
    }

    const aiScene &m_scene;
    const std::string &m_object;
    std::vector<Instance> m_instances;
    std::vector<std::string> m_names;  // "" for a node without meshes
    bool m_matched = false;
};

}  // namespace pelage::sim::assimp_walk
