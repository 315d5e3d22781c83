#include "sim/mesh/mesh_io.h"

#include <cctype>

#include "sim/core/input_error.h"

namespace pelage::sim {

TriangleMesh read_mesh(const std::string &path, MeshReadStats *stats) {
    const auto dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    for (char &c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == "off") return read_off(path, stats);
    if (ext == "obj") return read_obj(path, stats);
    throw InputError(
        path, 0, "",
        "unknown mesh extension '." + ext + "' (pelage reads .off and .obj)");
}

}  // namespace pelage::sim
