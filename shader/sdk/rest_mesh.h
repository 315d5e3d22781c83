// The mesh a plugin's view holds before any deformation or growth (the rest positions,
// exact doubles): the simulation's own surface when a .cells file was grown on it, its
// mesh hash being over these positions and triangles. The one copy the clonal mosaic
// (its pattern) and the renderer's fur layer (its rest surface) make.
#pragma once

#include <cstddef>
#include <cstdint>

#include "shader/pelage_shader.h"
#include "sim/mesh/mesh.h"

namespace pelage::shader::sdk {

// With `uvs`, the view's corner UVs too (when it has them), for texture regions
// resolved on the rest surface; the mosaic's pattern reads none.
inline sim::TriangleMesh rest_mesh(const PelageMeshView &view, bool uvs) {
    sim::TriangleMesh mesh;
    mesh.positions.resize(view.num_vertices);
    for (uint32_t v = 0; v < view.num_vertices; ++v)
        mesh.positions[v] = {view.rest_positions[3 * v], view.rest_positions[3 * v + 1],
                             view.rest_positions[3 * v + 2]};
    mesh.triangles.resize(view.num_triangles);
    for (uint32_t t = 0; t < view.num_triangles; ++t)
        for (int c = 0; c < 3; ++c) mesh.triangles[t][c] = view.triangles[3 * t + c];
    if (uvs && view.corner_uvs) {
        mesh.corner_uvs.resize(3 * size_t(view.num_triangles));
        for (size_t k = 0; k < mesh.corner_uvs.size(); ++k)
            mesh.corner_uvs[k] = {view.corner_uvs[2 * k], view.corner_uvs[2 * k + 1]};
    }
    return mesh;
}

}  // namespace pelage::shader::sdk
