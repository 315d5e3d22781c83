/* perlin: the gradient-noise baseline (Perlin 2002): fBm of improved noise on
 * object-space position, thresholded into two colours with a smooth step.
 *
 * The parameters and AOVs are the tables below (`pelage shaders perlin` prints them).
 */
#include <algorithm>
#include <memory>

#include "shader/perlin/perlin_noise.h"
#include "shader/sdk/create_guard.h"
#include "shader/sdk/object_space.h"
#include "shader/sdk/params.h"

namespace {

using namespace pelage::shader::perlin;
using namespace pelage::shader::sdk;

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

std::unique_ptr<Perlin> make(const PelageParamSet &ps) {
    const Params p(params, ps);
    auto n = std::make_unique<Perlin>(uint32_t(p.get_int("seed")));
    n->mesh.copy_from(ps.mesh);
    n->frequency = p.get_float("frequency");
    n->octaves = p.get_int("octaves");
    n->lacunarity = p.get_float("lacunarity");
    n->gain = p.get_float("gain");
    n->threshold = p.get_float("threshold");
    n->softness = p.get_float("softness");
    const auto spot = p.get_rgb("spot_colour"), base = p.get_rgb("base_colour");
    std::copy(spot.begin(), spot.end(), n->spot);
    std::copy(base.begin(), base.end(), n->base);
    return n;
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

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "perlin",
    "Perlin 2002 improved noise fBm, thresholded into spots (baseline)",
    params,
    aov_names,
    guarded_create<make>,
    shade,
    destroy_instance<Perlin>,
    nullptr,
    nullptr,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
