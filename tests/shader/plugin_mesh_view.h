// A shader plugin's mesh view (PelageMeshView) of a sim::TriangleMesh, filled as the
// renderer's Scene fills it (renderer/scene/scene.cpp): rendered and rest positions,
// triangles, corner UVs and the file's materials. It owns the arrays the view points
// into, so it outlives the plugin's `create`.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "shader/pelage_shader.h"
#include "sim/mesh/mesh.h"

namespace pelage::test {

struct PluginMeshView {
    std::vector<float> positions, corner_uvs;
    std::vector<double> rest_positions;
    std::vector<uint32_t> triangles;
    std::vector<PelageMeshMaterial> materials;
    sim::TriangleMesh mesh;
    std::string name;
    PelageMeshView view{};

    PluginMeshView(sim::TriangleMesh m, std::string mesh_name, const char *cells)
        : mesh(std::move(m)), name(std::move(mesh_name)) {
        for (const sim::Vec3d &v : mesh.positions) {
            positions.insert(positions.end(), {float(v.x), float(v.y), float(v.z)});
            rest_positions.insert(rest_positions.end(), {v.x, v.y, v.z});
        }
        for (const auto &t : mesh.triangles)
            triangles.insert(triangles.end(), t.begin(), t.end());
        for (const sim::Vec2d &uv : mesh.corner_uvs)
            corner_uvs.insert(corner_uvs.end(), {float(uv.x), float(uv.y)});
        for (const sim::MeshMaterial &mm : mesh.materials)
            materials.push_back(
                {mm.name.c_str(),
                 {float(mm.diffuse.x), float(mm.diffuse.y), float(mm.diffuse.z)},
                 mm.diffuse_texture.c_str()});
        view.num_vertices = uint32_t(mesh.num_vertices());
        view.num_triangles = uint32_t(mesh.num_triangles());
        view.positions = positions.data();
        view.rest_positions = rest_positions.data();
        view.triangles = triangles.data();
        view.corner_uvs = corner_uvs.empty() ? nullptr : corner_uvs.data();
        view.triangle_materials =
            mesh.triangle_material.empty() ? nullptr : mesh.triangle_material.data();
        view.materials = materials.data();
        view.num_materials = uint32_t(materials.size());
        view.cells_path = cells;
        view.mesh_name = name.c_str();
    }
    PluginMeshView(const PluginMeshView &) = delete;
    PluginMeshView &operator=(const PluginMeshView &) = delete;

    // One triangle in object space with corner UVs: for plugins that need a mesh's
    // presence more than its shape.
    static sim::TriangleMesh unit_triangle() {
        sim::TriangleMesh m;
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        m.triangles = {{0, 1, 2}};
        m.corner_uvs = {{0, 0}, {1, 0}, {0, 1}};
        return m;
    }

    // The renderer's warning callback: one line on stderr.
    static void warn(void *, const char *message) {
        std::fprintf(stderr, "%s\n", message);
    }
};

}  // namespace pelage::test
