#include "renderer/fur/comb_field.h"

#include <nlohmann/json.hpp>

#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"
#include "sim/mosaic/cell_types.h"

namespace pelage::renderer {

std::vector<float> comb_by_triangle(const sim::FieldSpec &spec,
                                    const sim::Surface &surface) {
    const size_t nt = surface.mesh.triangles.size();
    const sim::TangentField field = sim::resolve_field(spec, surface.crps, 1.0);
    std::vector<float> out(3 * nt, 0.0f);
    for (size_t t = 0; t < nt && t < field.a.size(); ++t) {
        // The triangle's local 2D frame is (x, z) of R_t p (sim/crps/crps.h), so a local
        // vector (a.x, a.y) is R_tᵀ (a.x, 0, a.y) in the mesh's space.
        const sim::Vec2d a = field.a[t];
        const sim::Vec3d v = surface.crps.frame(sim::TriId(t))
                                 .rotation.transpose_times(sim::Vec3d{a.x, 0, a.y});
        out[3 * t] = float(v.x);
        out[3 * t + 1] = float(v.y);
        out[3 * t + 2] = float(v.z);
    }
    return out;
}

sim::FieldSpec pattern_field(const std::string &cells_path, const std::string &field) {
    const sim::CellsData data = sim::read_cells_file(cells_path);
    const nlohmann::json params = nlohmann::json::parse(data.params_json, nullptr, false);
    if (!params.is_object() || !params.contains("preset"))
        throw InputError(cells_path, 0, field,
                         "\"field\" combs along the pattern's anisotropy field, but this "
                         ".cells file records no preset");
    const sim::Preset preset = sim::parse_preset(params["preset"].dump(), cells_path);
    if (preset.params.anisotropy_field.kind == sim::FieldSpec::Kind::none)
        throw InputError(
            cells_path, 0, field,
            "\"field\" combs along the pattern's anisotropy field, but preset "
            "\"" +
                preset.name +
                "\" has none (give the field itself, e.g. {\"along\": "
                "\"body_axis\"})");
    return preset.params.anisotropy_field;
}

}  // namespace pelage::renderer
