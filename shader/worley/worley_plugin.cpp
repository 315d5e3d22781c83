/* worley: the cellular-noise baseline (Worley 1996). Feature points fill object space;
 * each takes the spot type with probability `spot_fraction` (a hash of the point), and a
 * surface point gets the type of its nearest feature point: a two-colour Voronoi mosaic
 * of 3D cells cut by the surface, to compare with the Clonal Mosaic grown on it.
 *
 * The parameters and AOVs are the tables below (`pelage shaders worley` prints them).
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "shader/sdk/create_guard.h"
#include "shader/sdk/object_space.h"
#include "shader/sdk/params.h"
#include "shader/worley/worley_noise.h"

namespace {

using namespace pelage::shader::worley;
using namespace pelage::shader::sdk;

struct Worley {
    ObjectSpacePositions mesh;
    float frequency, mean_points, spot_fraction, spot[3], base[3], edge_width;
    uint32_t seed;
};

const PelageParamSpec params[] = {
    {"frequency",
     PELAGE_PARAM_FLOAT,
     {20, 0, 0},
     nullptr,
     1e-6f,
     1e6f,
     "feature cubes per object-space unit"},
    {"mean_points",
     PELAGE_PARAM_FLOAT,
     {3, 0, 0},
     nullptr,
     0.1f,
     8.0f,
     "Poisson mean of feature points per cube"},
    {"spot_fraction",
     PELAGE_PARAM_FLOAT,
     {0.3f, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "probability that a feature point is a spot"},
    {"spot_colour",
     PELAGE_PARAM_RGB,
     {0.08f, 0.04f, 0.02f},
     nullptr,
     0.0f,
     1.0f,
     "albedo of spot cells"},
    {"base_colour",
     PELAGE_PARAM_RGB,
     {0.8f, 0.55f, 0.3f},
     nullptr,
     0.0f,
     1.0f,
     "albedo of the other cells"},
    {"edge_width",
     PELAGE_PARAM_FLOAT,
     {0, 0, 0},
     nullptr,
     0.0f,
     1e6f,
     "soft boundary width, object units"},
    {"seed", PELAGE_PARAM_INT, {1, 0, 0}, nullptr, 0.0f, 2147483647.0f, "pattern seed"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};
const char *const aov_names[] = {"f1", "f2", "feature", nullptr};

bool is_spot(uint32_t feature, float fraction) {
    return (feature >> 8) * 0x1p-24f < fraction;
}

std::unique_ptr<Worley> make(const PelageParamSet &ps) {
    const Params p(params, ps);
    auto w = std::make_unique<Worley>();
    w->mesh.copy_from(ps.mesh);
    w->frequency = p.get_float("frequency");
    w->mean_points = p.get_float("mean_points");
    w->spot_fraction = p.get_float("spot_fraction");
    const auto spot = p.get_rgb("spot_colour"), base = p.get_rgb("base_colour");
    std::copy(spot.begin(), spot.end(), w->spot);
    std::copy(base.begin(), base.end(), w->base);
    w->edge_width = p.get_float("edge_width");
    w->seed = uint32_t(p.get_int("seed"));
    return w;
}

void shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const Worley &w = *static_cast<const Worley *>(self);
    float p[3];
    if (!w.mesh.position(*hit, p)) return;
    for (float &x : p) x *= w.frequency;
    const WorleyResult r = worley(p, w.seed, w.mean_points);
    const bool spot = is_spot(r.id1, w.spot_fraction);
    // Soft boundary: (F2 - F1)/2 is about the distance to the cell edge. The far side's
    // type is unknown from F1/F2 alone, so blend toward the mean of the two colours —
    // symmetric, hence continuous wherever the neighbour has the other type.
    const float width = std::max(w.edge_width, hit->footprint) * w.frequency;
    const float a =
        width > 0 ? 0.5f + 0.5f * smoothstep(0.0f, width, 0.5f * (r.f2 - r.f1)) : 1.0f;
    for (int k = 0; k < 3; ++k) {
        const float own = spot ? w.spot[k] : w.base[k],
                    mid = 0.5f * (w.spot[k] + w.base[k]);
        out->albedo[k] = a * own + (1 - a) * mid;
    }
    out->aov[0] = r.f1 / w.frequency;
    out->aov[1] = r.f2 / w.frequency;
    out->aov[2] = float(r.id1 & 0xffffffu);
    out->aov_written = 1;
}

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "worley",
    "Worley 1996 cellular noise, two-colour spots (baseline)",
    params,
    aov_names,
    guarded_create<make>,
    shade,
    destroy_instance<Worley>,
    nullptr,
    nullptr,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
