#include "sim/mesh/mesh_write_obj.h"

#include <charconv>
#include <string>

#include "sim/core/atomic_file.h"

namespace pelage::sim {
namespace {

// Shortest round-trip text of x (std::to_chars without a precision).
void put(std::string &line, double x) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof(buf), x);
    line += ' ';
    line.append(buf, r.ptr);
}

}  // namespace

void write_obj(const std::string &path, const TriangleMesh &mesh,
               const std::vector<Vec2d> &corner_uvs, const std::string &comment) {
    const bool uvs = !corner_uvs.empty(),
               normals = mesh.corner_normals.size() == 3 * mesh.num_triangles() &&
                         mesh.num_triangles() > 0;
    write_file_atomically(path, [&](std::ostream &out) {
        std::string line;
        if (!comment.empty()) out << "# " << comment << "\n";
        for (const Vec3d &p : mesh.positions) {
            line = "v";
            put(line, p.x);
            put(line, p.y);
            put(line, p.z);
            out << line << '\n';
        }
        for (const Vec2d &uv : corner_uvs) {
            line = "vt";
            put(line, uv.x);
            put(line, uv.y);
            out << line << '\n';
        }
        if (normals)
            for (const Vec3d &n : mesh.corner_normals) {
                line = "vn";
                put(line, n.x);
                put(line, n.y);
                put(line, n.z);
                out << line << '\n';
            }
        for (size_t t = 0; t < mesh.num_triangles(); ++t) {
            line = "f";
            for (int c = 0; c < 3; ++c) {
                const std::string corner = std::to_string(3 * t + c + 1);
                line += ' ' + std::to_string(mesh.triangles[t][c] + 1);
                if (uvs || normals) line += '/';
                if (uvs) line += corner;
                if (normals) line += '/' + corner;
            }
            out << line << '\n';
        }
    });
}

}  // namespace pelage::sim
