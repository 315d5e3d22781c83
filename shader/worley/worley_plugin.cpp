/* worley: the cellular-noise baseline (Worley 1996). Feature points fill object space;
 * each takes the spot type with probability `spot_fraction` (a hash of the point), and a
 * surface point gets the type of its nearest feature point: a two-colour Voronoi mosaic
 * of 3D cells cut by the surface, to compare with the Clonal Mosaic grown on it.
 *
 * | parameter     | type  | default           | meaning | | frequency     | float | 20 |
 * feature cubes per object-space unit            | | mean_points   | float | 3 | Poisson
 * mean of feature points per cube        | | spot_fraction | float | 0.3               |
 * probability that a feature point is a spot     | | spot_colour   | rgb   | (0.08, 0.04,
 * 0.02)| albedo of spot cells                           | | base_colour   | rgb   | (0.8,
 * 0.55, 0.3)  | albedo of the other cells                      | | edge_width    | float
 * | 0                 | soft boundary, object units (also antialiases) | | seed | int   |
 * 1                 | pattern seed                                   | AOVs: f1, f2
 * (object units), feature (hash of the nearest feature point, low 24 bits).
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "shader/object_space.h"
#include "shader/worley/worley_noise.h"

namespace {

using namespace pelage::shader;

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

void *create(const PelageParamSet *ps, PelageError *err) {
    auto w = std::make_unique<Worley>();
    w->mesh.copy_from(ps->mesh);
    const PelageParamValue *v = ps->values;  // table order, validated by the renderer
    w->frequency = v[0].f[0];
    w->mean_points = v[1].f[0];
    w->spot_fraction = v[2].f[0];
    std::copy(v[3].f, v[3].f + 3, w->spot);
    std::copy(v[4].f, v[4].f + 3, w->base);
    w->edge_width = v[5].f[0];
    w->seed = uint32_t(v[6].i);
    (void)err;
    return w.release();
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

void destroy(void *self) { delete static_cast<Worley *>(self); }

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "worley",
    "Worley 1996 cellular noise, two-colour spots (baseline)",
    params,
    aov_names,
    create,
    shade,
    destroy,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
