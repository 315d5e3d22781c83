/* The pelage shader plugin ABI. Plain C, versioned; exceptions never
 * cross it.
 *
 * A plugin is a shared library exporting one symbol, `pelage_shader_plugin`, which
 * returns a static descriptor. The renderer reads `abi` first and refuses the plugin when
 * it differs from PELAGE_SHADER_ABI; only then does it touch anything else.
 *
 * Lifetime: `create` is called once per scene object using the plugin, with the object's
 * validated parameters (every entry of `params`, defaults filled in, in table order) and
 * a read-only view of its mesh; it returns an instance or NULL with `err` filled. `shade`
 * is called at every hit, concurrently from many threads, with the same instance: it must
 * be thread-safe, must not allocate, block or throw. `destroy` frees the instance.
 *
 * Conventions: positions and normals in world space, normals unit length and facing the
 * incoming ray; colours are scene-linear Rec.709; lengths in scene units.
 */
#ifndef PELAGE_SHADER_H
#define PELAGE_SHADER_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PELAGE_SHADER_ABI 3u
#define PELAGE_SHADER_ENTRY "pelage_shader_plugin"
#define PELAGE_SHADER_AOV_SLOTS 4
#define PELAGE_SHADER_MATTE_SLOTS 3

#if defined(_WIN32)
#define PELAGE_EXPORT __declspec(dllexport)
#else
#define PELAGE_EXPORT __attribute__((visibility("default")))
#endif

typedef enum PelageParamType {
    PELAGE_PARAM_FLOAT = 1, /* one number */
    PELAGE_PARAM_INT = 2,   /* one integer */
    PELAGE_PARAM_RGB = 3,   /* [r, g, b], scene-linear */
    PELAGE_PARAM_STRING = 4 /* a string; paths are resolved by the plugin */
} PelageParamType;

/* One entry of a plugin's parameter table; a zeroed entry (name == NULL) ends it. */
typedef struct PelageParamSpec {
    const char *name;
    PelageParamType type;
    float default_value[3]; /* FLOAT uses [0], INT uses (int)[0], RGB uses all three */
    const char *default_string; /* STRING only */
    float min_value, max_value; /* inclusive range for FLOAT/INT/RGB components */
    const char *doc;            /* one line */
} PelageParamSpec;

/* A parameter value as handed to `create`. */
typedef struct PelageParamValue {
    const char *name;
    PelageParamType type;
    float f[3];
    int32_t i;
    const char *s;
} PelageParamValue;

/* A material of the mesh file (OBJ's .mtl, glTF's base colour, FBX's diffuse colour). */
typedef struct PelageMeshMaterial {
    const char *name;            /* never NULL */
    float diffuse[3];            /* scene-linear, as the file gives it */
    const char *diffuse_texture; /* absolute path, or "" when the material has none */
} PelageMeshMaterial;

/* A read-only view of the object's mesh (object space) and its optional .cells file,
 * valid during `create` only. Everything a plugin needs of the mesh is here: plugins
 * never open the mesh file. */
typedef struct PelageMeshView {
    uint32_t num_vertices, num_triangles;
    const float *positions;             /* 3 floats per vertex, as rendered (after any
                                           deformation or growth)                       */
    const double *rest_positions;       /* 3 doubles per vertex: the mesh as loaded and
                                           cleaned, before deformation or growth — exactly
                                           what `pelage sim` grows on, so a .cells file's
                                           mesh hash can be checked against it          */
    const uint32_t *triangles;          /* 3 indices per triangle                       */
    const float *corner_uvs;            /* 6 floats per triangle, or NULL               */
    const uint32_t *triangle_materials; /* per triangle an index into `materials`, or
                                           0xFFFFFFFF for none; NULL when the file has
                                           no materials */
    const PelageMeshMaterial *materials;
    uint32_t num_materials;
    uint32_t reserved;      /* zero */
    const char *cells_path; /* absolute path of the object's .cells, or NULL */
    const char *mesh_name;  /* the mesh reference of the scene (a path, "FILE#OBJECT" or
                               "procedural:..."), for messages only */
} PelageMeshView;

/* Prints one warning for the user on stderr, as given, once per process (an animation
   creates a plugin instance per frame). */
typedef void (*PelageWarnFn)(void *context, const char *message);

typedef struct PelageParamSet {
    uint32_t count;
    const PelageParamValue *values; /* the plugin's table order */
    uint32_t object_id;
    PelageMeshView mesh;
    const char *scene_dir;   /* folder of the scene file: relative paths in STRING
                                parameters resolve against it; "" when unknown */
    const char *object_name; /* the object's name in the scene (never NULL) */
    PelageWarnFn warn;       /* never NULL */
    void *warn_context;
} PelageParamSet;

typedef struct PelageError {
    char message[256];
} PelageError;

/* What the renderer knows at a hit. */
typedef struct PelageHit {
    uint32_t object_id, primitive_id;
    float b1, b2; /* barycentrics of corners 1 and 2; corner 0 has 1 - b1 - b2 */
    float p[3];   /* world-space position */
    float n[3];   /* world-space shading normal */
    float uv[2];  /* interpolated uv, (0, 0) unless has_uv */
    uint32_t has_uv;
    float footprint;   /* approximate ray footprint width at the hit, in the object's own
                          units (those of its mesh as loaded from its file, the rest
                          positions: the scene's divided by the object's scale and by
                          the pose's stretch of the triangle, when a clip or a skin's
                          default pose moves it), widened at rough bounces
                          (renderer/core/ray_cone.h) */
    uint32_t depth;    /* path vertex index, 0 for camera rays */
    uint32_t reserved; /* zero */
} PelageHit;

/* What a plugin returns. The renderer fills defaults before calling `shade`. The
 * eumelanin and pheomelanin concentrations and the cell type are typed fields (the fur
 * reads them at each strand's root); the AOV slots are for images only. */
typedef struct PelageShade {
    float albedo[3]; /* diffuse reflectance, [0, 1]; default (0.5, 0.5, 0.5) */
    float roughness; /* coat roughness override, < 0 keeps the material's */
    float eumelanin; /* pigment concentrations for fur; 0 by default */
    float pheomelanin;
    float aov[PELAGE_SHADER_AOV_SLOTS]; /* values of the `shader` AOV layer; 0 default */
    uint32_t aov_written;               /* set to 1 when aov[] was written */
    float ior; /* coat index of refraction override in [1, 3]; 0 keeps the material's.
                  0 is a zeroed field's value, so a plugin that never sets it leaves
                  the coat alone. */
    /* Ids in the plugin's matte layers (`matte_names`), for the Cryptomatte layers of
       the image; bit k of `matte_written` set when matte[k] holds one. Read at camera
       hits only. */
    uint32_t matte[PELAGE_SHADER_MATTE_SLOTS];
    uint32_t matte_written;
    /* The pattern's cell type at the hit (0-based, the plugin's own numbering; fur
       grooms per type), or -1 (default) when the plugin has no types. */
    int32_t cell_type;
} PelageShade;

/* The values a plugin's `shade` starts from: what a hit shows when the plugin writes
 * nothing. */
static inline PelageShade pelage_default_shade(void) {
    PelageShade s = {{0.5f, 0.5f, 0.5f}, -1.0f, 0.0f, 0.0f, {0, 0, 0, 0}, 0u, 0.0f,
                     {0u, 0u, 0u},       0u,    -1};
    return s;
}

typedef struct PelageShaderPlugin {
    uint32_t abi;                  /* == PELAGE_SHADER_ABI, checked at load */
    const char *name, *summary;    /* "diffuse"; one line for `pelage shaders` */
    const PelageParamSpec *params; /* {0}-terminated; drives validation and docs */
    const char *const *aov_names;  /* NULL-terminated, at most 4 names, or NULL */
    void *(*create)(const PelageParamSet *ps,
                    PelageError *err); /* NULL + err on failure */
    void (*shade)(const void *self, const PelageHit *hit, PelageShade *out);
    void (*destroy)(void *self);
    /* Matte layers (Cryptomatte, docs/guide/compositing-outputs.md): NULL-terminated, at
       most PELAGE_SHADER_MATTE_SLOTS names such as "type", or NULL. */
    const char *const *matte_names;
    /* The name of id `id` in matte layer `layer` of this instance, written
       NUL-terminated into `buf` (`size` bytes); returns 0 when the id is unknown. Names
       are global: the same name in two objects is one matte (a cell type shared by two
       animals), so names of per-object things include the object's name. Called after
       rendering, from one thread, once per id the image shows. NULL: every id is
       named "<object> <layer> <id>". */
    int (*matte_name)(const void *self, uint32_t layer, uint32_t id, char *buf,
                      uint32_t size);
} PelageShaderPlugin;

typedef const PelageShaderPlugin *(*PelageShaderEntry)(void);

#ifdef __cplusplus
}
static_assert(sizeof(PelageShade) == 68,
              "PelageShade is part of the ABI: bump PELAGE_SHADER_ABI");
static_assert(sizeof(PelageHit) == 64,
              "PelageHit is part of the ABI: bump PELAGE_SHADER_ABI");
#else
_Static_assert(sizeof(PelageShade) == 68, "PelageShade is part of the ABI");
_Static_assert(sizeof(PelageHit) == 64, "PelageHit is part of the ABI");
#endif

#endif /* PELAGE_SHADER_H */
