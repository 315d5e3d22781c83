/* A plugin built against ABI 2 (before the mesh view carried rest positions and
 * materials): the renderer must refuse it, asking for a rebuild, before reading anything
 * else of its descriptor. */
#include "shader/pelage_shader.h"

static const PelageParamSpec no_params[] = {{0}};
static const PelageShaderPlugin old = {
    2u, "old_abi", "built against ABI 2", no_params, 0, 0, 0, 0, 0, 0};

PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) { return &old; }
