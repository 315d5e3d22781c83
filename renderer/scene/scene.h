// A scene ready to render: the Embree geometry, per-object materials (a shader plugin
// instance plus the built-in BSDF it feeds), the lights and the camera. Built from a
// validated SceneDesc; plugin parameters are validated here, against each plugin's table.
#pragma once

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

  private:
    void build(const SceneDesc &desc, const PluginRegistry &plugins);
    void destroy_instances();

    SceneDesc m_desc;
    std::unique_ptr<EmbreeScene> m_geometry;
    std::unique_ptr<Lights> m_lights;
    std::vector<Material> m_materials;
    std::vector<std::string> m_aov_names;
    std::unique_ptr<FurGeometry> m_fur;
};

}  // namespace pelage::renderer
