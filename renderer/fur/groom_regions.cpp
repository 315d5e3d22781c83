#include "renderer/fur/groom_regions.h"

#include "sim/control/surface_control.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

std::vector<float> region_corners(const sim::ControlSpec &spec, const sim::Surface &rest,
                                  const std::string &scene_path,
                                  const std::string &field) {
    const size_t R = spec.region_names.size(), nt = rest.mesh.num_triangles();
    std::vector<float> out(3 * R * nt);
    if (R == 0) return out;
    try {
        const sim::SurfaceControl control(spec, rest.mesh, rest.crps, scene_path);
        for (size_t t = 0; t < nt; ++t)
            for (int c = 0; c < 3; ++c)
                for (size_t i = 0; i < R; ++i)
                    out[(3 * t + size_t(c)) * R + i] =
                        float(control.corner(int(i), sim::TriId(t), c));
    } catch (const InputError &e) {
        // SurfaceControl names a preset's paths ("regions.NAME"); here they sit in the
        // fur block of the scene file. (An unreadable texture names the image itself.)
        if (e.file() != scene_path) throw;
        throw e.under(field);
    }
    return out;
}

}  // namespace pelage::renderer
