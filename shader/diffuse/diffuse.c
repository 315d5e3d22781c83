/* diffuse: a constant albedo. The simplest pelage shader plugin, and the template for
 * the others.
 *
 * | parameter | type | default         | meaning                           |
 * | albedo    | rgb  | (0.5, 0.5, 0.5) | diffuse reflectance, each in [0,1] |
 */
#include <stdlib.h>

#include "shader/pelage_shader.h"

typedef struct Diffuse {
    float albedo[3];
} Diffuse;

static const PelageParamSpec diffuse_params[] = {
    {"albedo",
     PELAGE_PARAM_RGB,
     {0.5f, 0.5f, 0.5f},
     NULL,
     0.0f,
     1.0f,
     "diffuse reflectance (scene-linear Rec.709)"},
    {0},
};

static void *diffuse_create(const PelageParamSet *ps, PelageError *err) {
    Diffuse *d = (Diffuse *)malloc(sizeof(Diffuse));
    (void)err;
    if (!d) return NULL;
    for (int c = 0; c < 3; ++c) d->albedo[c] = ps->values[0].f[c];
    return d;
}

static void diffuse_shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const Diffuse *d = (const Diffuse *)self;
    (void)hit;
    out->albedo[0] = d->albedo[0];
    out->albedo[1] = d->albedo[1];
    out->albedo[2] = d->albedo[2];
}

static void diffuse_destroy(void *self) { free(self); }

static const PelageShaderPlugin diffuse_plugin = {
    PELAGE_SHADER_ABI, "diffuse",     "constant diffuse albedo", diffuse_params, NULL,
    diffuse_create,    diffuse_shade, diffuse_destroy,           NULL,           NULL,
};

PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &diffuse_plugin;
}
