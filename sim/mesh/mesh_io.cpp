#include "sim/mesh/mesh_io.h"

#include <assimp/Importer.hpp>
#include <cctype>

#include "sim/core/input_error.h"

namespace pelage::sim {
namespace {

std::string lower(std::string s) {
    for (char &c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string extension_of(const std::string &path) {
    const auto dot = path.find_last_of('.');
    const auto slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return "";
    return lower(path.substr(dot + 1));
}

// Asks assimp which extensions it imports; built once, never destroyed (it may be
// asked during static destruction).
const Assimp::Importer &assimp_formats() {
    static const Assimp::Importer *importer = new Assimp::Importer();
    return *importer;
}

}  // namespace

bool is_mesh_extension(const std::string &ext) {
    const std::string e = lower(ext);
    if (e == "off" || e == "obj" || e == "ply") return true;
    return !e.empty() && e.find_first_of("*;. ") == std::string::npos &&
           assimp_formats().IsExtensionSupported(e);
}

std::string mesh_extension_list() {
    std::string assimp;  // "*.3d;*.3ds;..."
    assimp_formats().GetExtensionList(assimp);
    std::string out = "off, obj";
    for (size_t start = 0; start < assimp.size();) {
        size_t end = assimp.find(';', start);
        if (end == std::string::npos) end = assimp.size();
        std::string e = assimp.substr(start, end - start);
        if (e.rfind("*.", 0) == 0) e = e.substr(2);
        if (!e.empty() && e != "off" && e != "obj") out += ", " + e;
        start = end + 1;
    }
    return out;
}

TriangleMesh read_mesh(const std::string &path, MeshReadStats *stats,
                       const std::string &object) {
    const std::string ext = extension_of(path);
    if (ext == "off" || ext == "ply") {
        if (!object.empty())
            throw InputError(path, 0, "",
                             "a ." + ext +
                                 " file holds one unnamed object: it has no "
                                 "object \"" +
                                 object + "\" to select");
        return ext == "off" ? read_off(path, stats) : read_ply(path, stats);
    }
    if (ext == "obj") return read_obj(path, stats, object);
    if (is_mesh_extension(ext)) return read_assimp(path, stats, object);
    throw InputError(path, 0, "",
                     "unknown mesh extension '." + ext + "' (pelage reads " +
                         mesh_extension_list() + ")");
}

}  // namespace pelage::sim
