#include "renderer/geometry/deform.h"

#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer {

void apply_pose(sim::TriangleMesh &rest, const std::string &pose_path, float weight,
                const std::string &scene_path, const std::string &field) {
    sim::TriangleMesh pose;
    try {
        pose = sim::load_mesh(pose_path);
    } catch (const InputError &e) {
        throw InputError(
            e.file(), e.line(), e.field(),
            std::string(e.what()).substr(std::string(e.what()).find(": ") + 2) + " (" +
                field + " in " + scene_path + ")");
    }
    // --- Same topology: vertex count, triangle count and every index ---
    auto mismatch = [&](const std::string &what) {
        throw InputError(
            scene_path, 0, field,
            "\"" + pose_path + "\" does not have the rest mesh's topology: " + what);
    };
    if (pose.num_vertices() != rest.num_vertices())
        mismatch(std::to_string(pose.num_vertices()) + " vertices, the rest mesh has " +
                 std::to_string(rest.num_vertices()));
    if (pose.num_triangles() != rest.num_triangles())
        mismatch(std::to_string(pose.num_triangles()) + " triangles, the rest mesh has " +
                 std::to_string(rest.num_triangles()));
    for (size_t t = 0; t < rest.num_triangles(); ++t)
        if (pose.triangles[t] != rest.triangles[t])
            mismatch("triangle " + std::to_string(t) + " has other vertices");
    // --- Blend the positions ---
    const double w = weight;
    for (size_t v = 0; v < rest.num_vertices(); ++v)
        rest.positions[v] = rest.positions[v] * (1 - w) + pose.positions[v] * w;
    if (w > 0) rest.corner_normals.clear();
}

}  // namespace pelage::renderer
