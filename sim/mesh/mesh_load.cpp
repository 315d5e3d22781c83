#include "sim/mesh/mesh_load.h"

#include <cstdio>
#include <mutex>
#include <set>

#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

// Files of several objects loaded whole are noted once per process: a render job loads
// the same file for its pattern's growth, its geometry and each deformation.
void note_merged_objects(const std::string &path, const MeshReadStats &read) {
    if (read.pieces_read < 2) return;
    static std::mutex mutex;
    static std::set<std::string> noted;
    const std::lock_guard<std::mutex> lock(mutex);
    if (!noted.insert(path).second) return;
    std::string names;
    for (size_t i = 0; i < read.object_names.size() && i < 8; ++i)
        names += (i ? ", " : "") + read.object_names[i];
    if (read.object_names.size() > 8) names += ", ...";
    std::fprintf(stderr,
                 "pelage: %s: merged its %zu objects into one mesh (names: %s); select "
                 "one with %s#NAME\n",
                 path.c_str(), read.pieces_read, names.empty() ? "none" : names.c_str(),
                 path.c_str());
}

}  // namespace

TriangleMesh load_mesh(const std::string &path_or_spec, MeshLoadReport *report,
                       const MeshCleanOptions &clean) {
    MeshLoadReport local;
    MeshLoadReport &r = report ? *report : local;
    r = {};
    static const std::string prefix = "procedural:";
    TriangleMesh raw;
    if (path_or_spec.rfind(prefix, 0) == 0) {
        raw = make_procedural(path_or_spec.substr(prefix.size()));
    } else {
        const MeshSpec spec = parse_mesh_spec(path_or_spec);
        raw = read_mesh(spec.path, &r.read, spec.object);
        if (spec.object.empty()) note_merged_objects(spec.path, r.read);
    }
    r.raw_vertices = raw.num_vertices();
    r.raw_triangles = raw.num_triangles();
    return clean_mesh(raw, path_or_spec, clean, &r.clean);
}

}  // namespace pelage::sim
