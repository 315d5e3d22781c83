/* A plugin built against a future ABI: the renderer must refuse it, naming the file. */
#include "shader/pelage_shader.h"

static const PelageParamSpec no_params[] = {{0}};
static const PelageShaderPlugin bad = {
    999u, "bad_abi", "wrong ABI on purpose", no_params, 0, 0, 0, 0, 0, 0};

PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) { return &bad; }
