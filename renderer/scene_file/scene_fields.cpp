#include "renderer/scene_file/scene_fields.h"

#include <algorithm>

namespace pelage::renderer {

namespace {

// In the order of the reference tables of docs/guide/scene-format.md; then the fields
// those describe in prose. The fur block has its own reader and page (scene_fur.h,
// docs/guide/fur.md).
constexpr SceneField fields[] = {
    {"camera", "type", FieldUse::value, "camera", "`type`",
     "`\"pinhole\"` | `\"thin_lens\"`", "`\"pinhole\"`", "projection"},
    {"camera", "position", FieldUse::value, "camera", "`position`", "vector",
     "`[0, 1, 5]`", "the eye"},
    {"camera", "look_at", FieldUse::value, "camera", "`look_at`", "vector", "`[0, 0, 0]`",
     "the point at the centre of the image; must differ from `position`"},
    {"camera", "up", FieldUse::value, "camera", "`up`", "vector", "`[0, 1, 0]`",
     "the image's up direction; must not be parallel to the view"},
    {"camera", "fov", FieldUse::value, "camera", "`fov`", "number in [0.01, 179]", "40",
     "vertical field of view, degrees"},
    {"camera", "aperture_radius", FieldUse::value, "camera", "`aperture_radius`",
     "number ≥ 0", "0", "thin lens only: the lens radius in scene units (0 = pinhole)"},
    {"camera", "focus_distance", FieldUse::value, "camera", "`focus_distance`",
     "number ≥ 0", "0",
     "thin lens only: the distance in focus; 0 = the distance to `look_at`"},
    {"film", "width", FieldUse::value, "film", "`width`, `height`",
     "integer in [1, 65536]", "640, 360", "pixels"},
    {"film", "height", FieldUse::value, "film", "", "", "", ""},
    {"film", "spp", FieldUse::value, "film", "`spp`", "integer in [1, 1048576]", "16",
     "samples per pixel (the most, with adaptive sampling); powers of two suit the "
     "stratified sampler best"},
    {"film", "noise_threshold", FieldUse::value, "film", "`noise_threshold`",
     "number in [0, 1]", "0",
     "adaptive sampling: after each pass of samples (1, 1, 2, 4, ... from `min_spp` on), "
     "pixels whose noise — the standard error of their mean luminance over the square "
     "root of that luminance — is below this stop, unless a neighbour goes on; 0 = off. "
     "0.01 gives a clean image, 0.1 a preview; the EXR records `pelage:noise_threshold`, "
     "`pelage:min_spp` and `pelage:mean_spp`"},
    {"film", "min_spp", FieldUse::value, "film", "`min_spp`", "integer in [1, 1048576]",
     "16", "adaptive sampling: samples every pixel takes before it may stop"},
    {"film.filter", "type", FieldUse::value, "film", "`filter.type`",
     "`\"box\"` | `\"gaussian\"` | `\"blackman_harris\"`", "`\"gaussian\"`",
     "pixel reconstruction filter"},
    {"film.filter", "radius", FieldUse::value, "film", "`filter.radius`",
     "number in [0.5, 8]", "0.5 box, 1.5 gaussian (σ = r/3), 2 Blackman-Harris",
     "filter radius, pixels"},
    {"film", "output", FieldUse::output, "film", "`output`", "path", "none",
     "the EXR written when `-o` is not given"},
    {"film", "preview", FieldUse::output, "film", "`preview`", "path", "none",
     "a PNG or JPEG preview written when `--preview` is not given"},
    {"film", "pixel_type", FieldUse::value, "film", "`pixel_type`",
     "`\"half\"` | `\"float\"`", "`\"half\"`",
     "storage of the colour layers of the EXR (depth, ids and shader layers are always "
     "float)"},
    {"film", "view", FieldUse::value, "film", "`view`", "string", "`\"Standard\"`",
     "the OpenColorIO view of the preview (`Standard`, `Filmic`, `Raw` in pelage's own "
     "config)"},
    {"film", "layers", FieldUse::value, "film", "`layers`", "object", "all written",
     "per AOV layer (`albedo`, `N`, `depth`, `id`, `shader`): `\"half\"`, `\"float\"` or "
     "`false` (not written); `id` and `shader` refuse `\"half\"`"},
    {"film", "compression", FieldUse::value, "film", "`compression`",
     "`\"none\"` | `\"rle\"` | `\"zips\"` | `\"zip\"` | `\"piz\"` | `\"pxr24\"` | "
     "`\"b44\"` | `\"b44a\"` | `\"dwaa\"` | `\"dwab\"`",
     "`\"zip\"`", "the EXR's compression"},
    {"film", "cryptomatte", FieldUse::value, "film", "`cryptomatte`",
     "`true` | `false` | list", "`false`",
     "Cryptomatte layers: `true` for all the materials offer, or a list of `\"object\"`, "
     "`\"type\"`, `\"cell\"`, `\"lineage\"`"},
    {"film", "cryptomatte_ranks", FieldUse::value, "film", "`cryptomatte_ranks`",
     "integer in [1, 16]", "6", "(id, coverage) pairs per pixel and layer"},
    {"lights", "type", FieldUse::value, "lights", "`type`",
     "`\"environment\"` | `\"distant\"` | `\"sphere\"` | `\"quad\"`", "required", ""},
    {"lights", "colour", FieldUse::value, "lights", "`colour`", "colour ≥ 0", "1", ""},
    {"lights", "intensity", FieldUse::value, "lights", "`intensity`", "number ≥ 0", "1",
     "radiance = `colour` × `intensity` (irradiance for a distant light)"},
    {"objects", "name", FieldUse::value, "objects", "`name`", "string", "`\"objectN\"`",
     "used by turntables and error messages"},
    {"objects", "mesh", FieldUse::input, "objects", "`mesh`",
     "path, `path#object` or `procedural:` name", "required", "the surface (below)"},
    {"objects", "transform", FieldUse::value, "objects", "`transform`", "object",
     "identity", "placement in the scene (below)"},
    {"objects", "normals", FieldUse::value, "objects", "`normals`",
     "`\"auto\"` | `\"smooth\"` | `\"flat\"`", "`\"auto\"`",
     "shading normals: the mesh file's vertex normals when it has them (`auto`), "
     "area-weighted vertex normals (`smooth`), or the face normal (`flat`)"},
    {"objects", "cells", FieldUse::input, "objects", "`cells`", "path", "none",
     "the object's `.cells` file from `pelage sim` (grown on this mesh or another of its "
     "shape), handed to its shader plugin (required by `clonal_mosaic`)"},
    {"objects", "pattern", FieldUse::value, "objects", "`pattern`", "object", "none",
     "how `cells` is grown: `{\"preset\": NAME or file, \"seed\": N}` (seed default 1; a "
     "preset file is relative to the scene). `pelage render`, `compare` and `bench` grow "
     "the pattern into `cells` when that file is missing or was grown from another "
     "preset (by content), seed or mesh (by content), and use it as it is otherwise; the "
     "log says which. Needs `cells`."},
    {"objects", "material", FieldUse::value, "objects", "`material`", "object",
     "diffuse grey", "below"},
    {"objects", "fur", FieldUse::value, "objects", "`fur`", "object", "none",
     "strands grown on the object, see [fur.md](fur.md)"},
    {"objects", "deform", FieldUse::input, "objects", "`deform`",
     "path or array of paths", "none", "deformed poses (below)"},
    {"objects", "grow", FieldUse::value, "objects", "`grow`", "object", "none",
     "the mesh at an age of a preset's `growth` block, `{\"preset\", \"from\", \"to\"}` "
     "(below)"},
    {"objects", "animation", FieldUse::value, "objects", "`animation`", "object", "none",
     "a clip of the mesh file played on the object, `{\"clip\", \"fps\", \"loop\", "
     "\"start\"}` (below)"},
    {"objects.transform", "scale", FieldUse::value, "transform", "`scale`",
     "number > 0, or vector", "", "uniform or per-axis scale"},
    {"objects.transform", "rotate", FieldUse::value, "transform", "`rotate`",
     "`[degrees, ax, ay, az]`", "", "rotation about the axis (ax, ay, az)"},
    {"objects.transform", "translate", FieldUse::value, "transform", "`translate`",
     "vector", "", ""},
    {"objects.transform", "matrix", FieldUse::value, "transform", "`matrix`",
     "12 numbers", "", "a row-major 3×4 affine matrix; conflicts with the three above"},
    {"objects.material", "shader", FieldUse::value, "material", "`shader`", "plugin name",
     "`\"diffuse\"`",
     "the plugin that gives the albedo (and pigments, AOVs, coat overrides) at each hit; "
     "`pelage shaders` lists the installed ones"},
    {"objects.material", "params", FieldUse::value, "material", "`params`", "object",
     "`{}`",
     "the plugin's parameters, checked against its table (unknown names, types, ranges); "
     "`pelage shaders NAME` prints the table"},
    {"objects.material", "bsdf", FieldUse::value, "material", "`bsdf`",
     "`\"lambert\"` | `\"coated\"`", "`\"lambert\"`", "the scattering model"},
    {"objects.material", "roughness", FieldUse::value, "material", "`roughness`",
     "number in [0, 1]", "0.3", "`coated` only: the coat's GGX roughness"},
    {"objects.material", "ior", FieldUse::value, "material", "`ior`", "number in [1, 3]",
     "1.5", "`coated` only: the coat's index of refraction"},
    {"integrator", "max_depth", FieldUse::value, "integrator", "`max_depth`",
     "integer in [1, 1024]", "8", "scattering events per path; 1 = direct light only"},
    {"integrator", "rr_depth", FieldUse::value, "integrator", "`rr_depth`",
     "integer in [1, 1024]", "3", "Russian roulette from this depth on"},
    {"integrator", "light_selection", FieldUse::value, "integrator", "`light_selection`",
     "`\"auto\"` | `\"all\"` | `\"power\"` | `\"uniform\"`", "`\"auto\"`",
     "which lights next-event estimation samples at a vertex: every one (`all`; what "
     "`auto` does for up to 4 lights), or one chosen by power or uniformly (`auto` above "
     "4)"},
    {"integrator", "clamp_indirect", FieldUse::value, "integrator", "`clamp_indirect`",
     "number ≥ 0", "0",
     "firefly clamping, off at 0: the light a sample gathers beyond direct light at its "
     "first hit is scaled down to at most this in its brightest channel. It removes "
     "fireflies but darkens (biased); the EXR records `pelage:clamp_indirect`"},
    {"integrator", "sampler", FieldUse::value, "integrator", "`sampler`",
     "`\"sobol\"` | `\"independent\"`", "`\"sobol\"`",
     "the random numbers: Owen-scrambled Sobol points, stratified over each pixel's "
     "samples (use a power of two for `spp`), or independent white noise (for "
     "comparison)"},
    {"animation", "frames", FieldUse::value, "animation", "`frames`",
     "integer in [1, 10⁶]", "1", "frame count"},
    {"animation", "first_frame", FieldUse::value, "animation", "`first_frame`",
     "integer in [0, 10⁸]", "0",
     "the number of the first frame: the frames are `first_frame` … `first_frame + "
     "frames − 1` (1001 … 1120 as VFX numbers them); motion, poses and the sampler use "
     "*f* − `first_frame`, so renumbering changes no pixel"},
    {"animation", "fps", FieldUse::value, "animation", "`fps`", "number", "24",
     "frame rate, recorded in every frame and used by `pelage movie`"},
    {"animation.turntable", "axis", FieldUse::value, "animation", "`turntable.axis`",
     "vector", "`[0, 1, 0]`", "the axis of the turn"},
    {"animation.turntable", "center", FieldUse::value, "animation", "`turntable.center`",
     "vector", "`[0, 0, 0]`", "a point on the axis"},
    {"animation.turntable", "degrees", FieldUse::value, "animation",
     "`turntable.degrees`", "number in [−36000, 36000]", "360",
     "the turn over the whole animation: frame *f* is at `degrees` × (*f* − "
     "`first_frame`) / `frames` (a 360° loop does not repeat frame 0)"},
    {"animation.turntable", "target", FieldUse::value, "animation", "`turntable.target`",
     "`\"camera\"` | `\"object\"`", "`\"camera\"`",
     "orbit the camera (the scene appears to turn the other way), or turn objects"},
    {"animation.turntable", "objects", FieldUse::value, "animation",
     "`turntable.objects`", "array of object names", "all",
     "object target only: the objects that turn"},
    {"animation", "shutter", FieldUse::value, "animation", "`shutter`",
     "`[open, close]` within [0, 1]", "`[0, 0]`",
     "motion blur over this part of each frame: the camera of a camera turntable and "
     "every object playing a clip move during it (below)"},
    {"animation", "motion_steps", FieldUse::value, "animation", "`motion_steps`",
     "integer in [2, 129]", "2",
     "the times in the shutter a clip's object is posed at (evenly spaced, open to "
     "close); it moves linearly between them"},
    {"animation.turntable", "shutter", FieldUse::value, "animation",
     "`turntable.shutter`", "`[open, close]` within [0, 1]", "`[0, 0]`",
     "the older spelling of `shutter`, camera target only; giving both is an error"},
    // Described in prose, not in a reference table.
    {"", "camera", FieldUse::value},
    {"", "film", FieldUse::value},
    {"", "lights", FieldUse::value},
    {"", "objects", FieldUse::value},
    {"", "integrator", FieldUse::value},
    {"", "animation", FieldUse::value},
    {"film.layers", "albedo", FieldUse::value},
    {"film.layers", "N", FieldUse::value},
    {"film.layers", "depth", FieldUse::value},
    {"film.layers", "id", FieldUse::value},
    {"film.layers", "shader", FieldUse::value},
    {"lights", "image", FieldUse::input},
    {"lights", "rotation", FieldUse::value},
    {"lights", "direction", FieldUse::value},
    {"lights", "angle", FieldUse::value},
    {"lights", "center", FieldUse::value},
    {"lights", "radius", FieldUse::value},
    {"lights", "corner", FieldUse::value},
    {"lights", "edge_u", FieldUse::value},
    {"lights", "edge_v", FieldUse::value},
    {"lights", "two_sided", FieldUse::value},
    {"objects.pattern", "preset", FieldUse::input},
    {"objects.pattern", "seed", FieldUse::value},
    {"objects.grow", "preset", FieldUse::input},
    {"objects.grow", "from", FieldUse::value},
    {"objects.grow", "to", FieldUse::value},
    {"objects.animation", "clip", FieldUse::value},
    {"objects.animation", "fps", FieldUse::value},
    {"objects.animation", "loop", FieldUse::value},
    {"objects.animation", "start", FieldUse::value},
    {"animation", "turntable", FieldUse::value},
};

// A table cell's text: a literal '|' would end the cell.
std::string cell(std::string_view s) {
    std::string out;
    for (const char c : s) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

}  // namespace

std::span<const SceneField> scene_fields() { return fields; }

const SceneField *scene_field(std::string_view block, std::string_view key) {
    for (const SceneField &f : fields)
        if (f.block == block && f.key == key) return &f;
    return nullptr;
}

std::vector<std::string> scene_field_keys(std::string_view block) {
    std::vector<std::string> keys;
    for (const SceneField &f : fields)
        if (f.block == block) keys.emplace_back(f.key);
    return keys;
}

std::string scene_block_of(std::string_view json_path) {
    std::string block;
    bool in_index = false;
    for (const char c : json_path) {
        if (c == '[') in_index = true;
        if (!in_index) block += c;
        if (c == ']') in_index = false;
    }
    return block;
}

std::vector<std::string> scene_field_tables() {
    std::vector<std::string> tables;
    for (const SceneField &f : fields)
        if (!f.table.empty() &&
            std::find(tables.begin(), tables.end(), f.table) == tables.end())
            tables.emplace_back(f.table);
    return tables;
}

std::string scene_fields_markdown(std::string_view table) {
    bool defaults = false;
    for (const SceneField &f : fields)
        if (f.table == table && !f.shown.empty())
            defaults = defaults || !f.fallback.empty();
    std::string out =
        defaults ? "| field | type | default | meaning |\n| --- | --- | --- | --- |\n"
                 : "| field | type | meaning |\n| --- | --- | --- |\n";
    for (const SceneField &f : fields) {
        if (f.table != table || f.shown.empty()) continue;
        out += "| " + cell(f.shown) + " | " + cell(f.type) + " |";
        if (defaults) out += " " + cell(f.fallback) + " |";
        out += (f.meaning.empty() ? "" : " " + cell(f.meaning)) + " |\n";
    }
    return out;
}

}  // namespace pelage::renderer
