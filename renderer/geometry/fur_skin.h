// What one object's fur grows on in one frame: its world-space triangles and shading
// normals, its rest shape in this frame's placement (a posed skin keeps the roots grown
// on its rest shape), the comb turned with the object and the groom's region weights,
// as the SkinMesh that renderer/fur grows strands on. The layer's parameters come with
// it: the comb direction in world space and the unset defaults scaled to the object.
#pragma once

#include <cstddef>
#include <vector>

#include "renderer/fur/fur_params.h"
#include "renderer/fur/root_sampling.h"
#include "renderer/geometry/embree_scene.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

class FurSkin {
  public:
    // Object `object` of `desc` at the shutter's opening. Throws pelage::InputError
    // naming objects[i].fur.comb or .regions when the comb field or the regions cannot
    // be resolved on the skin.
    FurSkin(const SceneDesc &desc, size_t object, const ObjectGeometry &og);
    // The same skin at later motion step `step` of the shutter (MeshData's
    // later_positions): the same triangles, moved, with the comb carried along.
    FurSkin(const FurSkin &opening, const ObjectGeometry &og, unsigned step);
    FurSkin(const FurSkin &) = delete;
    FurSkin &operator=(const FurSkin &) = delete;

    const FurParams &params() const { return m_params; }
    // Points into this object's own buffers: valid while it lives.
    const SkinMesh &mesh() const { return m_mesh; }

  private:
    FurParams m_params;
    std::vector<float> m_positions, m_normals;  // world space
    std::vector<float> m_rest_positions;        // posed skins only
    std::vector<float> m_comb;                  // world space, per triangle corner
    std::vector<float> m_regions;               // per corner and region
    SkinMesh m_mesh;
};

}  // namespace pelage::renderer
