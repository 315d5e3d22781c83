// A scene ready to render: the Embree geometry, per-object materials (a shader plugin
// instance plus the built-in BSDF it feeds), the lights and the camera. Built from a
// validated SceneDesc; plugin parameters are validated here, against each plugin's table.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "renderer/camera/camera.h"
#include "renderer/geometry/embree_scene.h"
#include "renderer/geometry/fur_geometry.h"
#include "renderer/lights/lights.h"
#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct Material {
    const PelageShaderPlugin *plugin = nullptr;
    void *instance = nullptr;
    MaterialDesc::Bsdf bsdf = MaterialDesc::Bsdf::lambert;
    float roughness = 0.3f, ior = 1.5f;
    float coat_F_int = 0;  // BsdfCoated::internal_diffuse_reflectance(ior), coated only
    float coat_S = 0;      // BsdfCoated::specular_albedo(roughness, ior), coated only
};

class Scene {
  public:
    Scene(const SceneDesc &desc, const PluginRegistry &plugins);
    ~Scene();
    Scene(const Scene &) = delete;
    Scene &operator=(const Scene &) = delete;

    const SceneDesc &desc() const { return m_desc; }
    const EmbreeScene &geometry() const { return *m_geometry; }
    const Lights &lights() const { return *m_lights; }
    const std::vector<Material> &materials() const { return m_materials; }  // per object
    // Names of the `shader` AOV slots (from the first plugin in the scene that has any).
    const std::vector<std::string> &shader_aov_names() const { return m_aov_names; }
    // The scene's fur (renderer/geometry/fur_geometry.h), or null when no object has any.
    const FurGeometry *fur() const { return m_fur.get(); }
    // What object `object`'s material shows at a point of its mesh (world-space p and
    // unit n): its plugin's shade as an indirect hit sees it (depth 1, so no blend
    // across cell edges). Fur roots take their pigment from it; exports their colours.
    PelageShade shade_surface(size_t object, const SurfacePoint &s, Vec3f p,
                              Vec3f n) const;
    // Whether anything moves during the shutter (its fur moves with its mesh).
    bool moves() const { return m_geometry->moves(); }

    // Cryptomatte: the film's matte layers ("object", then plugin layers such as
    // "type"), at most 1 + PELAGE_SHADER_MATTE_SLOTS, as film.cryptomatte asks.
    const std::vector<std::string> &matte_layers() const { return m_matte_layers; }
    // The slot of `layer` in object `object`'s plugin matte ids (PelageShade::matte),
    // or -1 when its plugin has no such layer; -2 for the object layer itself.
    int matte_slot(uint32_t object, int layer) const {
        return m_matte_slot[object][size_t(layer)];
    }
    static constexpr int object_layer = -2;
    // The name of a Cryptomatte key of `layer` (Film: object index, or object << 32 |
    // the plugin's id).
    std::string matte_name(int layer, uint64_t key) const;

  private:
    void build(const SceneDesc &desc, const PluginRegistry &plugins);
    void choose_matte_layers(const SceneDesc &desc);
    void destroy_instances();

    SceneDesc m_desc;
    std::unique_ptr<EmbreeScene> m_geometry;
    std::unique_ptr<Lights> m_lights;
    std::vector<Material> m_materials;
    std::vector<std::string> m_aov_names;
    std::unique_ptr<FurGeometry> m_fur;
    std::vector<std::string> m_matte_layers;
    std::vector<std::array<int8_t, 1 + PELAGE_SHADER_MATTE_SLOTS>> m_matte_slot;
};

}  // namespace pelage::renderer
