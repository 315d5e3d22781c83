#include "pattern/statistics/mask_adherence.h"

#include <optional>

#include "sim/control/surface_control.h"
#include "sim/crps/surface_sampling.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mosaic/preset.h"

namespace pelage::pattern::statistics {

std::vector<MaskAdherence> measure_mask_adherence(const mosaic::MosaicPattern &pattern,
                                                  const std::string &mesh_path,
                                                  const sim::Preset &preset,
                                                  const std::string &preset_file,
                                                  size_t samples, uint64_t seed) {
    const sim::ControlSpec &spec = preset.control;
    std::vector<MaskAdherence> out(spec.masks.size());
    if (spec.masks.empty()) return out;
    const sim::Surface &surface = pattern.surface();
    // A simplified simulation surface lacks the input's attributes and UVs: the input
    // (the pattern's render mesh) carries them.
    std::optional<sim::TriangleMesh> input;
    if (pattern.transfer() && spec.needs_mesh_data()) input = sim::load_mesh(mesh_path);
    const sim::SurfaceControl control(spec, surface.mesh, surface.crps, preset_file,
                                      input ? &*input : nullptr);
    std::vector<size_t> zero(spec.masks.size(), 0), wrong(spec.masks.size(), 0);
    size_t found = 0;
    for (const auto &s : sim::sample_surface_uniform(surface.crps, samples, seed)) {
        const mosaic::ClosestCell c =
            pattern.index().find_nearest(s.tri, {float(s.p.x), float(s.p.y)});
        if (c.index == mosaic::ClosestCell::none) continue;
        ++found;
        const int type = pattern.cells().type[c.index];
        for (size_t k = 0; k < spec.masks.size(); ++k) {
            if (control.mask(spec.masks[k], s.tri, s.p) > 0) continue;
            ++zero[k];
            if (type == spec.masks[k].type) ++wrong[k];
        }
    }
    for (size_t k = 0; k < spec.masks.size(); ++k) {
        const sim::MaskSpec &m = spec.masks[k];
        MaskAdherence &a = out[k];
        a.type = preset.types[m.type].name;
        a.otherwise = preset.types[m.otherwise].name;
        a.region = spec.region_names[size_t(m.region)];
        a.only_in = m.inside;
        a.masked_out_samples = zero[k];
        a.masked_out_share = found ? double(zero[k]) / double(found) : 0.0;
        a.violation = zero[k] ? double(wrong[k]) / double(zero[k]) : 0.0;
    }
    return out;
}

}  // namespace pelage::pattern::statistics
