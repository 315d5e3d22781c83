// The clonal_mosaic plugin opened from the build's plugin folder and created for a mesh
// and a .cells file through the plugin ABI, as the renderer's Scene does it: what the
// plugin and bake tests call.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/mesh/mesh_load.h"
#include "tests/shader/plugin_mesh_view.h"

namespace pelage::test {

struct MosaicPluginInstance {
    renderer::LoadedPlugin plugin;
    renderer::PluginParams params;
    PluginMeshView view;
    const sim::TriangleMesh &mesh = view.mesh;
    void *self = nullptr;  // null when create() refused; `error` says why
    std::string error;

    // `cells` may be null (no .cells file given). The view names the mesh `mesh_name`
    // (`mesh_path` when empty), as the scene does; the plugin only prints it.
    MosaicPluginInstance(const nlohmann::json &p, const char *cells,
                         const std::string &mesh_path, const std::string &mesh_name = "")
        : plugin(renderer::open_plugin(renderer::package_lib_dir() +
                                       "/shaders/clonal_mosaic.so")),
          params(
              renderer::validate_plugin_params(*plugin.desc, p, "test.json", "params")),
          view(sim::load_mesh(mesh_path), mesh_name.empty() ? mesh_path : mesh_name,
               cells) {
        PelageParamSet ps{};
        ps.count = uint32_t(params.values.size());
        ps.values = params.values.data();
        ps.mesh = view.view;
        ps.warn = PluginMeshView::warn;
        PelageError err{};
        self = plugin.desc->create(&ps, &err);
        error = err.message;
    }
    ~MosaicPluginInstance() {
        if (self) plugin.desc->destroy(self);
    }
    MosaicPluginInstance(const MosaicPluginInstance &) = delete;
    MosaicPluginInstance &operator=(const MosaicPluginInstance &) = delete;

    PelageShade shade(uint32_t prim, float b1, float b2, float footprint = 0,
                      uint32_t depth = 0) const {
        PelageHit hit{};
        hit.depth = depth;
        hit.primitive_id = prim;
        hit.b1 = b1;
        hit.b2 = b2;
        hit.footprint = footprint;
        PelageShade out{};
        out.roughness = -1;
        out.cell_type = -1;
        plugin.desc->shade(self, &hit, &out);
        return out;
    }
};

}  // namespace pelage::test
