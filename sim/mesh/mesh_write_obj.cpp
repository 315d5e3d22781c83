#include "sim/mesh/mesh_write_obj.h"

#include <cstdio>

#include "sim/core/atomic_file.h"

namespace pelage::sim {

void write_obj(const std::string &path, const TriangleMesh &mesh,
               const std::vector<Vec2d> &corner_uvs, const std::string &comment) {
    write_file_atomically(path, [&](std::ostream &out) {
        char line[256];
        if (!comment.empty()) out << "# " << comment << "\n";
        for (const Vec3d &p : mesh.positions) {
            std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
            out << line;
        }
        for (const Vec2d &uv : corner_uvs) {
            std::snprintf(line, sizeof(line), "vt %.9g %.9g\n", uv.x, uv.y);
            out << line;
        }
        for (size_t t = 0; t < mesh.num_triangles(); ++t) {
            const auto &tri = mesh.triangles[t];
            if (corner_uvs.empty())
                std::snprintf(line, sizeof(line), "f %u %u %u\n", tri[0] + 1, tri[1] + 1,
                              tri[2] + 1);
            else
                std::snprintf(line, sizeof(line), "f %u/%zu %u/%zu %u/%zu\n", tri[0] + 1,
                              3 * t + 1, tri[1] + 1, 3 * t + 2, tri[2] + 1, 3 * t + 3);
            out << line;
        }
    });
}

}  // namespace pelage::sim
