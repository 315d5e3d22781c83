#include "sim/mesh/mesh_load.h"

#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {

TriangleMesh load_mesh(const std::string &path_or_spec, MeshLoadReport *report,
                       const MeshCleanOptions &clean) {
    MeshLoadReport local;
    MeshLoadReport &r = report ? *report : local;
    r = {};
    static const std::string prefix = "procedural:";
    const TriangleMesh raw = path_or_spec.rfind(prefix, 0) == 0
                                 ? make_procedural(path_or_spec.substr(prefix.size()))
                                 : read_mesh(path_or_spec, &r.read);
    r.raw_vertices = raw.num_vertices();
    r.raw_triangles = raw.num_triangles();
    return clean_mesh(raw, path_or_spec, clean, &r.clean);
}

}  // namespace pelage::sim
