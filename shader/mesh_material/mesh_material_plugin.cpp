/* mesh_material: the mesh file's own materials. Each triangle takes the diffuse colour
 * of its material (OBJ's Kd from the .mtl, glTF's baseColorFactor, FBX's or Collada's
 * diffuse colour) times the material's diffuse texture at the hit's UV (map_Kd, the base
 * colour texture), as the MTL and glTF specifications multiply them. Texels are taken as
 * stored (like the texture plugin), through OpenImageIO's TextureSystem, repeating
 * outside [0, 1].
 *
 * The renderer hands the file's materials and each triangle's material in the mesh view
 * (PelageMeshView::materials, triangle_materials).
 *
 * | parameter | type | default         | meaning                                       |
 * | default   | rgb  | (0.5, 0.5, 0.5) | albedo of triangles the file gives no material |
 * | textures  | int  | 1               | 1: multiply by the material's texture; 0: not  |
 */
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shader/pelage_shader.h"
#include "shader/sdk/create_guard.h"
#include "shader/sdk/params.h"

namespace {

using namespace pelage::shader::sdk;

struct MeshMaterials {
    std::vector<uint32_t> material;            // per triangle; invalid_id = none
    std::vector<std::array<float, 3>> colour;  // per material, then the default
    std::vector<OIIO::TextureSystem::TextureHandle *> texture;  // per material or null
    std::shared_ptr<OIIO::TextureSystem> system;
};

const PelageParamSpec params[] = {
    {"default",
     PELAGE_PARAM_RGB,
     {0.5f, 0.5f, 0.5f},
     nullptr,
     0.0f,
     1.0f,
     "albedo of the triangles the mesh file gives no material"},
    {"textures",
     PELAGE_PARAM_INT,
     {1, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "1: multiply each material's colour by its diffuse texture (needs UVs); 0: colours "
     "only"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

std::unique_ptr<MeshMaterials> make(const PelageParamSet &ps) {
    const Params p(params, ps);
    if (!ps.mesh.triangle_materials || ps.mesh.num_materials == 0)
        throw std::invalid_argument(
            std::string(ps.mesh.mesh_name ? ps.mesh.mesh_name : "the mesh") +
            " defines no materials (an OBJ needs its .mtl)");
    auto m = std::make_unique<MeshMaterials>();
    m->material.assign(ps.mesh.triangle_materials,
                       ps.mesh.triangle_materials + ps.mesh.num_triangles);
    const bool textures = p.get_int("textures") != 0;
    for (uint32_t k = 0; k < ps.mesh.num_materials; ++k) {
        const PelageMeshMaterial &mm = ps.mesh.materials[k];
        const std::string name = mm.name, texture = mm.diffuse_texture;
        m->colour.push_back({std::clamp(mm.diffuse[0], 0.0f, 1.0f),
                             std::clamp(mm.diffuse[1], 0.0f, 1.0f),
                             std::clamp(mm.diffuse[2], 0.0f, 1.0f)});
        OIIO::TextureSystem::TextureHandle *handle = nullptr;
        if (textures && !texture.empty()) {
            if (!ps.mesh.corner_uvs)
                throw std::invalid_argument(
                    "material \"" + name + "\" has the texture " + texture +
                    " but the mesh has no UVs (set \"textures\": 0)");
            if (!std::filesystem::exists(texture))
                throw std::invalid_argument("material \"" + name + "\": no such image " +
                                            texture);
            // The process-wide shared texture system, as in the texture plugin (a
            // private one would go through OIIO 2.4's mis-sized delete).
            if (!m->system) {
                m->system = std::shared_ptr<OIIO::TextureSystem>(
                    OIIO::TextureSystem::create(true), [](OIIO::TextureSystem *) {});
                m->system->attribute("automip", 1);
            }
            const OIIO::ustring file(texture);
            m->system->invalidate(file, false);
            handle = m->system->get_texture_handle(file);
            if (!handle || !m->system->imagespec(handle, nullptr))
                throw std::runtime_error(texture +
                                         ": cannot read: " + m->system->geterror());
        }
        m->texture.push_back(handle);
    }
    const std::array<float, 3> def = p.get_rgb("default");
    m->colour.push_back(def);
    return m;
}

void shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const MeshMaterials &m = *static_cast<const MeshMaterials *>(self);
    const uint32_t k = hit->primitive_id < m.material.size()
                           ? m.material[hit->primitive_id]
                           : 0xFFFFFFFFu;
    const size_t slot = k < m.texture.size() ? k : m.colour.size() - 1;
    float rgb[3] = {m.colour[slot][0], m.colour[slot][1], m.colour[slot][2]};
    if (slot < m.texture.size() && m.texture[slot] && hit->has_uv) {
        OIIO::TextureOpt opt;
        opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
        float texel[3] = {1, 1, 1};
        // OBJ's v runs bottom to top, images top to bottom.
        m.system->texture(m.texture[slot], nullptr, opt, hit->uv[0], 1.0f - hit->uv[1], 0,
                          0, 0, 0, 3, texel);
        for (int c = 0; c < 3; ++c) rgb[c] *= std::clamp(texel[c], 0.0f, 1.0f);
    }
    for (int c = 0; c < 3; ++c) out->albedo[c] = rgb[c];
}

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "mesh_material",
    "the mesh file's own materials: each triangle's diffuse colour and texture",
    params,
    nullptr,
    guarded_create<make>,
    shade,
    destroy_instance<MeshMaterials>,
    nullptr,
    nullptr,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
