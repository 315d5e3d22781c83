/* perlin: the gradient-noise baseline (Perlin 2002): fBm of improved noise on
 * object-space position, thresholded into two colours with a smooth step.
 *
 * | parameter   | type  | default            | meaning | | frequency   | float | 8 | base
 * frequency per object-space unit        | | octaves     | int   | 4                  |
 * fBm octaves                                 | | lacunarity  | float | 2 | frequency
 * factor per octave                 | | gain        | float | 0.5                |
 * amplitude factor per octave                 | | threshold   | float | 0.15 | noise
 * value above which a point is a spot   | | softness    | float | 0.03               |
 * half-width of the smooth step, noise units  | | spot_colour | rgb   | (0.08, 0.04,
 * 0.02) | albedo of spots                             | | base_colour | rgb   | (0.8,
 * 0.55, 0.3)   | albedo elsewhere                            | | seed        | int   | 1
 * | permutation seed                            | AOVs: noise (the fBm value).
 */
#include <algorithm>
#include <memory>

#include "shader/object_space.h"
#include "shader/perlin/perlin_noise.h"

namespace {

using namespace pelage::shader;

struct Perlin {
    Perlin(uint32_t seed) : noise(seed) {}
    PerlinNoise noise;
    ObjectSpacePositions mesh;
    float frequency, lacunarity, gain, threshold, softness, spot[3], base[3];
    int octaves;
};

const PelageParamSpec params[] = {
    {"frequency",
     PELAGE_PARAM_FLOAT,
     {8, 0, 0},
     nullptr,
     1e-6f,
     1e6f,
     "base frequency per object-space unit"},
    {"octaves", PELAGE_PARAM_INT, {4, 0, 0}, nullptr, 1.0f, 16.0f, "fBm octaves"},
    {"lacunarity",
     PELAGE_PARAM_FLOAT,
     {2, 0, 0},
     nullptr,
     1.0f,
     8.0f,
     "frequency factor per octave"},
    {"gain",
     PELAGE_PARAM_FLOAT,
     {0.5f, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "amplitude factor per octave"},
    {"threshold",
     PELAGE_PARAM_FLOAT,
     {0.15f, 0, 0},
     nullptr,
     -1.0f,
     1.0f,
     "noise value above which a point is a spot"},
    {"softness",
     PELAGE_PARAM_FLOAT,
     {0.03f, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "half-width of the smooth step"},
    {"spot_colour",
     PELAGE_PARAM_RGB,
     {0.08f, 0.04f, 0.02f},
     nullptr,
     0.0f,
     1.0f,
     "albedo of spots"},
    {"base_colour",
     PELAGE_PARAM_RGB,
     {0.8f, 0.55f, 0.3f},
     nullptr,
     0.0f,
     1.0f,
     "albedo elsewhere"},
    {"seed",
     PELAGE_PARAM_INT,
     {1, 0, 0},
     nullptr,
     0.0f,
     2147483647.0f,
     "permutation seed"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};
const char *const aov_names[] = {"noise", nullptr};

void *create(const PelageParamSet *ps, PelageError *err) {
    const PelageParamValue *v = ps->values;  // table order, validated by the renderer
    auto p = std::make_unique<Perlin>(uint32_t(v[8].i));
    p->mesh.copy_from(ps->mesh);
    p->frequency = v[0].f[0];
    p->octaves = v[1].i;
    p->lacunarity = v[2].f[0];
    p->gain = v[3].f[0];
    p->threshold = v[4].f[0];
    p->softness = v[5].f[0];
    std::copy(v[6].f, v[6].f + 3, p->spot);
    std::copy(v[7].f, v[7].f + 3, p->base);
    (void)err;
    return p.release();
}

void shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const Perlin &p = *static_cast<const Perlin *>(self);
    float x[3];
    if (!p.mesh.position(*hit, x)) return;
    const float n = p.noise.fbm(x[0] * p.frequency, x[1] * p.frequency,
                                x[2] * p.frequency, p.octaves, p.lacunarity, p.gain);
    const float s = smoothstep(p.threshold - p.softness, p.threshold + p.softness, n);
    for (int k = 0; k < 3; ++k) out->albedo[k] = s * p.spot[k] + (1 - s) * p.base[k];
    out->aov[0] = n;
    out->aov_written = 1;
}

void destroy(void *self) { delete static_cast<Perlin *>(self); }

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "perlin",
    "Perlin 2002 improved noise fBm, thresholded into spots (baseline)",
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
