#include "apps/explore/view_mesh.h"

#include <cstring>

namespace pelage::renderer::explore {
namespace {

template <class T>
void put(std::vector<uint8_t> &out, const T &v) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &v, sizeof(T));
}

}  // namespace

std::vector<uint8_t> view_mesh_bytes(const sim::TriangleMesh &mesh,
                                     const TypeTextureLayout &l) {
    const size_t n = mesh.num_triangles();
    std::vector<sim::Vec3d> normal(mesh.positions.size(), sim::Vec3d{0, 0, 0});
    for (const auto &t : mesh.triangles) {
        const sim::Vec3d a = mesh.positions[t[0]], b = mesh.positions[t[1]],
                         c = mesh.positions[t[2]];
        const sim::Vec3d f = cross(b - a, c - a);  // twice the area, along the normal
        for (sim::VertId v : t) normal[v] = normal[v] + f;
    }
    std::vector<uint8_t> out;
    out.reserve(4 + n * 24 * 4);
    put(out, uint32_t(n));
    for (const auto &t : mesh.triangles)
        for (sim::VertId v : t)
            for (double x :
                 {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z})
                put(out, float(x));
    for (const auto &t : mesh.triangles)
        for (sim::VertId v : t) {
            const double len = length(normal[v]);
            const sim::Vec3d u = len > 0 ? normal[v] / len : sim::Vec3d{0, 1, 0};
            for (double x : {u.x, u.y, u.z}) put(out, float(x));
        }
    for (float uv : l.corner_uvs) put(out, uv);
    return out;
}

}  // namespace pelage::renderer::explore
