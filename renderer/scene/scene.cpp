#include "renderer/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "renderer/bsdf/bsdf_coated.h"
#include "renderer/core/setup_phase.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

Scene::Scene(const SceneDesc &desc, const PluginRegistry &plugins) : m_desc(desc) {
    // A constructor that throws never runs its destructor: plugin instances created
    // before the failure (e.g. fur asking for too many strands) are released here.
    try {
        build(m_desc, plugins);
    } catch (...) {
        destroy_instances();
        throw;
    }
}

void Scene::build(const SceneDesc &desc, const PluginRegistry &plugins) {
    // --- Check every material's shader and parameters before loading any mesh ---
    std::vector<const LoadedPlugin *> chosen;
    std::vector<PluginParams> params;
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        const std::string field = "objects[" + std::to_string(i) + "].material";
        const LoadedPlugin &p =
            plugins.get(desc.objects[i].material.shader, desc.path, field + ".shader");
        params.push_back(validate_plugin_params(*p.desc, desc.objects[i].material.params,
                                                desc.path, field + ".params"));
        chosen.push_back(&p);
    }
    for (size_t i = 0; i < desc.objects.size(); ++i)
        if (const std::string &c = desc.objects[i].cells;
            !c.empty() && !std::filesystem::is_regular_file(c))
            throw InputError(c, 0, "",
                             "cannot open file (objects[" + std::to_string(i) +
                                 "].cells in " + desc.path + ")");
    m_geometry = std::make_unique<EmbreeScene>(desc);
    m_lights = std::make_unique<Lights>(desc.lights, m_geometry->bounding_radius(),
                                        desc.integrator.light_selection);

    m_materials.resize(desc.objects.size());
    // The mosaic plugin loads its .cells file and builds its index here.
    std::optional<SetupPhase> phase(std::in_place, "setting up shaders");
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        const ObjectDesc &o = desc.objects[i];
        const MeshData &mesh = *m_geometry->objects()[i].mesh;
        PelageParamSet ps{};
        ps.count = uint32_t(params[i].values.size());
        ps.values = params[i].values.data();
        ps.object_id = uint32_t(i);
        ps.mesh.num_vertices = mesh.num_vertices;
        ps.mesh.num_triangles = mesh.num_triangles;
        ps.mesh.positions = mesh.object_positions.data();
        ps.mesh.rest_positions = mesh.rest->positions.data();
        ps.mesh.triangles = mesh.triangles.data();
        ps.mesh.corner_uvs = mesh.corner_uvs.empty() ? nullptr : mesh.corner_uvs.data();
        std::vector<PelageMeshMaterial> materials;
        for (const sim::MeshMaterial &mm : mesh.rest->materials)
            materials.push_back(
                {mm.name.c_str(),
                 {float(mm.diffuse.x), float(mm.diffuse.y), float(mm.diffuse.z)},
                 mm.diffuse_texture.c_str()});
        ps.mesh.materials = materials.data();
        ps.mesh.num_materials = uint32_t(materials.size());
        ps.mesh.triangle_materials = mesh.rest->triangle_material.empty()
                                         ? nullptr
                                         : mesh.rest->triangle_material.data();
        ps.mesh.cells_path = o.cells.empty() ? nullptr : o.cells.c_str();
        ps.mesh.mesh_name = o.mesh.c_str();
        ps.scene_dir = desc.dir.c_str();
        ps.object_name = o.name.c_str();
        // A plugin's warning is printed once per process: an animation builds a Scene
        // per frame, and the same note on every frame would bury the others.
        ps.warn = [](void *, const char *message) {
            static std::mutex mutex;
            static std::set<std::string> printed;
            const std::lock_guard<std::mutex> lock(mutex);
            if (printed.insert(message).second) std::fprintf(stderr, "%s\n", message);
        };
        PelageError err{};
        Material &m = m_materials[i];
        m.plugin = chosen[i]->desc;
        m.instance = m.plugin->create(&ps, &err);
        if (!m.instance) {
            err.message[sizeof(err.message) - 1] = 0;
            throw InputError(desc.path, 0, "objects[" + std::to_string(i) + "].material",
                             std::string("shader \"") + m.plugin->name + "\" (" +
                                 chosen[i]->file + ") refused its parameters: " +
                                 (err.message[0] ? err.message : "no reason given"));
        }
        m.bsdf = o.material.bsdf;
        m.roughness = o.material.roughness;
        m.ior = o.material.ior;
        if (m.bsdf == MaterialDesc::Bsdf::coated) {
            m.coat_F_int = BsdfCoated::internal_diffuse_reflectance(m.ior);
            m.coat_S = BsdfCoated::specular_albedo(m.roughness, m.ior);
        }
        if (m_aov_names.empty() && m.plugin->aov_names)
            for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && m.plugin->aov_names[k]; ++k)
                m_aov_names.push_back(m.plugin->aov_names[k]);
    }
    choose_matte_layers(desc);
    phase.reset();
    // --- Fur: strands grown from each furry object's skin, added to the Embree scene ---
    for (const ObjectDesc &o : desc.objects)
        if (o.fur) {
            // Each root's colour and pigment: the skin's own material plugin there.
            const auto pigment = [this](size_t i, const SurfacePoint &s, Vec3f p,
                                        Vec3f n) {
                const PelageShade sh = shade_surface(i, s, p, n);
                RootPigment rp;
                rp.colour = {sh.albedo[0], sh.albedo[1], sh.albedo[2]};
                rp.eumelanin = sh.eumelanin;
                rp.pheomelanin = sh.pheomelanin;
                // Matte ids only when the film keeps Cryptomatte (16 bytes a strand).
                if (!m_desc.film.cryptomatte.empty()) {
                    for (int k = 0; k < PELAGE_SHADER_MATTE_SLOTS; ++k)
                        rp.matte[k] = sh.matte[k];
                    rp.matte_written = sh.matte_written;
                }
                rp.cell_type = std::max(sh.cell_type, -1);
                return rp;
            };
            m_fur = std::make_unique<FurGeometry>(desc, *m_geometry, pigment);
            if (m_fur->layers().empty()) m_fur.reset();
            break;
        }
}

void Scene::choose_matte_layers(const SceneDesc &desc) {
    // Every matte layer some object's plugin offers, in the order first offered.
    std::vector<std::string> offered = {"object"};
    for (const Material &m : m_materials)
        for (int k = 0; m.plugin->matte_names && k < PELAGE_SHADER_MATTE_SLOTS &&
                        m.plugin->matte_names[k];
             ++k)
            if (std::find(offered.begin(), offered.end(), m.plugin->matte_names[k]) ==
                offered.end())
                offered.push_back(m.plugin->matte_names[k]);
    const std::vector<std::string> &asked = desc.film.cryptomatte;
    if (asked.size() == 1 && asked[0] == "*") {
        m_matte_layers = offered;
    } else {
        for (size_t i = 0; i < asked.size(); ++i) {
            if (std::find(offered.begin(), offered.end(), asked[i]) == offered.end()) {
                std::string all;
                for (const std::string &o : offered) all += (all.empty() ? "" : ", ") + o;
                throw InputError(desc.path, 0,
                                 "film.cryptomatte[" + std::to_string(i) + "]",
                                 "no object's material offers a \"" + asked[i] +
                                     "\" matte; this scene offers: " + all);
            }
        }
        m_matte_layers = asked;
    }
    if (m_matte_layers.size() > size_t(1 + PELAGE_SHADER_MATTE_SLOTS))
        throw InputError(desc.path, 0, "film.cryptomatte",
                         "at most " + std::to_string(1 + PELAGE_SHADER_MATTE_SLOTS) +
                             " Cryptomatte layers");
    m_matte_slot.assign(m_materials.size(), {});
    for (size_t o = 0; o < m_materials.size(); ++o)
        for (size_t l = 0; l < m_matte_layers.size(); ++l) {
            int slot = -1;
            if (m_matte_layers[l] == "object") slot = object_layer;
            const PelageShaderPlugin &p = *m_materials[o].plugin;
            for (int k = 0; slot == -1 && p.matte_names &&
                            k < PELAGE_SHADER_MATTE_SLOTS && p.matte_names[k];
                 ++k)
                if (m_matte_layers[l] == p.matte_names[k]) slot = k;
            m_matte_slot[o][l] = int8_t(slot);
        }
}

PelageShade Scene::shade_surface(size_t object, const SurfacePoint &s, Vec3f p,
                                 Vec3f n) const {
    const Material &mat = m_materials[object];
    PelageHit hit{};
    hit.object_id = uint32_t(object);
    hit.primitive_id = s.triangle;
    hit.b1 = s.b1;
    hit.b2 = s.b2;
    hit.p[0] = p.x, hit.p[1] = p.y, hit.p[2] = p.z;
    hit.n[0] = n.x, hit.n[1] = n.y, hit.n[2] = n.z;
    hit.depth = 1;  // not a camera hit: no antialiasing blend across cell edges
    PelageShade sh = pelage_default_shade();
    mat.plugin->shade(mat.instance, &hit, &sh);
    return sh;
}

std::string Scene::matte_name(int layer, uint64_t key) const {
    const size_t object = size_t(key >> 32);
    if (m_matte_slot.empty() || size_t(layer) >= m_matte_layers.size()) return "";
    if (m_matte_layers[size_t(layer)] == "object") {
        const size_t o = size_t(key);
        return o < m_desc.objects.size() ? m_desc.objects[o].name : "";
    }
    if (object >= m_materials.size()) return "";
    const Material &m = m_materials[object];
    const int slot = m_matte_slot[object][size_t(layer)];
    const uint32_t id = uint32_t(key);
    if (m.plugin->matte_name) {
        char buf[512];
        if (m.plugin->matte_name(m.instance, uint32_t(slot), id, buf, sizeof buf))
            return buf;
    }
    return m_desc.objects[object].name + " " + m_matte_layers[size_t(layer)] + " " +
           std::to_string(id);
}

Scene::~Scene() { destroy_instances(); }

void Scene::destroy_instances() {
    for (Material &m : m_materials)
        if (m.instance) m.plugin->destroy(m.instance), m.instance = nullptr;
}

}  // namespace pelage::renderer
