/* A test plugin: writes its hit's ids and footprint into the shader AOV slots and returns
 * a NaN albedo on every third primitive, so tests can check the AOV path, the footprints
 * plugins are given, and that no NaN reaches the film. */
#include <math.h>
#include <stdlib.h>

#include "shader/pelage_shader.h"

static const PelageParamSpec probe_params[] = {
    {"offset",
     PELAGE_PARAM_FLOAT,
     {7.0f, 0, 0},
     NULL,
     0.0f,
     100.0f,
     "added to the object id"},
    {0},
};
static const char *const probe_aovs[] = {"prim", "object_plus_offset", "footprint", NULL};

static void *probe_create(const PelageParamSet *ps, PelageError *err) {
    float *offset = (float *)malloc(sizeof(float));
    (void)err;
    if (offset) *offset = ps->values[0].f[0];
    return offset;
}

static void probe_shade(const void *self, const PelageHit *hit, PelageShade *out) {
    out->aov[0] = (float)hit->primitive_id;
    out->aov[1] = (float)hit->object_id + *(const float *)self;
    out->aov[2] = hit->footprint;
    out->aov_written = 1;
    out->albedo[0] = out->albedo[1] = out->albedo[2] =
        hit->primitive_id % 3 == 0 ? NAN : 0.5f;
}

static void probe_destroy(void *self) { free(self); }

static const PelageShaderPlugin probe = {
    PELAGE_SHADER_ABI, "aov_probe", "test: ids into AOVs", probe_params, probe_aovs,
    probe_create,      probe_shade, probe_destroy,         NULL,         NULL};

PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) { return &probe; }
