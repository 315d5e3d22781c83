#include "sim/run/cells_data.h"

#include <algorithm>

namespace pelage::sim {

static_assert(static_cast<uint32_t>(max_cell_types) == cells_file_max_types,
              "a .cells file holds as many types as a mosaic has");

CellsFileType cells_file_type(const CellType &t) {
    return {t.name,        t.colour,        t.eumelanin,
            t.pheomelanin, t.division_time, t.initial_probability};
}

std::vector<CellsFileType> cells_file_types(const CellTypes &types) {
    std::vector<CellsFileType> out;
    out.reserve(types.types().size());
    for (const CellType &t : types.types()) out.push_back(cells_file_type(t));
    return out;
}

CellsData make_cells_data(const TriangleMesh &mesh, const Crps &crps,
                          const CellTypes &types, const Cells &cells,
                          const std::string &params_json, uint64_t seed) {
    CellsData d;
    d.mesh_hash = mesh_hash(mesh);
    d.seed = seed;
    d.params_json = params_json;
    d.types = cells_file_types(types);
    const size_t nt = crps.num_triangles();
    d.frames.reserve(nt);
    for (TriId t = 0; t < nt; ++t) d.frames.push_back(crps.frame(t));
    const Topology &topo = crps.topology();
    d.nbr_row = topo.nbr_row;
    d.nbr = topo.nbr;
    d.to_master.reserve(topo.nbr.size());
    for (TriId t = 0; t < nt; ++t)
        for (const RigidMap2 &F : crps.to_master(t)) d.to_master.push_back(F);
    // Cells sorted by (triangle, id): buckets hold ids in history order, so sort each.
    d.cell_row.assign(nt + 1, 0);
    const size_t n = cells.size();
    d.x.reserve(n);
    d.z.reserve(n);
    d.type.reserve(n);
    d.id.reserve(n);
    d.founder.reserve(n);
    std::vector<CellId> ids;
    for (TriId t = 0; t < nt; ++t) {
        ids = cells.on(t);
        std::sort(ids.begin(), ids.end());
        for (CellId c : ids) {
            d.x.push_back(cells.pos(c).x);
            d.z.push_back(cells.pos(c).y);
            d.type.push_back(cells.type(c));
            d.id.push_back(c);
            d.founder.push_back(cells.founder(c));
        }
        d.cell_row[t + 1] = static_cast<uint32_t>(d.x.size());
    }
    return d;
}

nlohmann::json recorded_anisotropy_field(const nlohmann::json &preset) {
    if (preset.is_object() && preset.contains("simulation")) {
        const nlohmann::json &s = preset["simulation"];
        if (s.is_object() && s.contains("anisotropy")) {
            const nlohmann::json &a = s["anisotropy"];
            if (a.is_object() && a.contains("field")) return a["field"];
        }
    }
    return nullptr;
}

}  // namespace pelage::sim
