// A second implementation of glTF 2.0 posing, written in the tests straight from the
// specification (§3.6 accessors, §3.7.2.2 morph targets, §3.7.3 skins, §3.11 animations)
// with nothing of assimp or renderer/animation: the JSON is read with nlohmann-json and
// the accessors decoded by hand. It is the independent reference the rig is checked
// against.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pelage::test {

class GltfReference {
  public:
    using Vec3 = std::array<double, 3>;
    // Reads a .gltf (buffers in files next to it or as data: URIs) or a .glb.
    explicit GltfReference(const std::string &path);

    // Every triangle of every mesh primitive placed by a node, in document order of the
    // nodes' preorder walk from the scene's roots (meshes' primitives in order), with
    // its corners posed at `seconds` into animation `animation` (−1: the rest pose,
    // nodes as the file places them).
    std::vector<std::array<Vec3, 3>> triangles(int animation, double seconds) const;
    int animation(const std::string &name) const;

  private:
    using Mat4 = std::array<double, 16>;  // column-major, as glTF stores matrices
    std::vector<double> accessor(int index, int *components) const;
    Mat4 local(int node, int animation, double seconds) const;
    nlohmann::json m_doc;
    std::vector<std::string> m_buffers;
};

}  // namespace pelage::test
