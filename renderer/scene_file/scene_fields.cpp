#include "renderer/scene_file/scene_fields.h"

#include <algorithm>
#include <stdexcept>

namespace pelage::renderer {

namespace {

// In the order of the reference tables of docs/guide/scene-format.md and
// docs/guide/fur.md; then the fields those describe in prose.
constexpr SceneField fields[] = {
    {"camera",
     "type",
     FieldUse::value,
     "camera",
     "`type`",
     {"`\"pinhole\"` | `\"thin_lens\"`", "`\"pinhole\"`", "projection"}},
    {"camera",
     "position",
     FieldUse::value,
     "camera",
     "`position`",
     {"vector", "`[0, 1, 5]`", "the eye"}},
    {"camera",
     "look_at",
     FieldUse::value,
     "camera",
     "`look_at`",
     {"vector", "`[0, 0, 0]`",
      "the point at the centre of the image; must differ from `position`"}},
    {"camera",
     "up",
     FieldUse::value,
     "camera",
     "`up`",
     {"vector", "`[0, 1, 0]`",
      "the image's up direction; must not be parallel to the view"}},
    {"camera",
     "fov",
     FieldUse::value,
     "camera",
     "`fov`",
     {"number in [0.01, 179]", "40", "vertical field of view, degrees"}},
    {"camera",
     "aperture_radius",
     FieldUse::value,
     "camera",
     "`aperture_radius`",
     {"number ≥ 0", "0", "thin lens only: the lens radius in scene units (0 = pinhole)"}},
    {"camera",
     "focus_distance",
     FieldUse::value,
     "camera",
     "`focus_distance`",
     {"number ≥ 0", "0",
      "thin lens only: the distance in focus; 0 = the distance to `look_at`"}},
    {"film",
     "width",
     FieldUse::value,
     "film",
     "`width`, `height`",
     {"integer in [1, 65536]", "640, 360", "pixels"}},
    {"film", "height", FieldUse::value, "film"},
    {"film",
     "spp",
     FieldUse::value,
     "film",
     "`spp`",
     {"integer in [1, 1048576]", "16",
      "samples per pixel (the most, with adaptive sampling); powers of two suit the "
      "stratified sampler best"}},
    {"film",
     "noise_threshold",
     FieldUse::value,
     "film",
     "`noise_threshold`",
     {"number in [0, 1]", "0",
      "adaptive sampling: after each pass of samples (1, 1, 2, 4, ... from `min_spp` "
      "on), pixels whose noise — the standard error of their mean luminance over the "
      "square root of that luminance — is below this stop, unless a neighbour goes on; 0 "
      "= off. 0.01 gives a clean image, 0.1 a preview; the EXR records "
      "`pelage:noise_threshold`, `pelage:min_spp` and `pelage:mean_spp`"}},
    {"film",
     "min_spp",
     FieldUse::value,
     "film",
     "`min_spp`",
     {"integer in [1, 1048576]", "16",
      "adaptive sampling: samples every pixel takes before it may stop"}},
    {"film",
     "denoise",
     FieldUse::value,
     "film",
     "`denoise`",
     {"boolean", "false",
      "denoise the beauty from the film's two half buffers (`--denoise`): the EXR keeps "
      "the noisy `R G B A` and adds `denoised.R denoised.G denoised.B`; the preview "
      "shows the denoised image (docs/guide/compositing-outputs.md)"}},
    {"film.filter",
     "type",
     FieldUse::value,
     "film",
     "`filter.type`",
     {"`\"box\"` | `\"gaussian\"` | `\"blackman_harris\"`", "`\"gaussian\"`",
      "pixel reconstruction filter"}},
    {"film.filter",
     "radius",
     FieldUse::value,
     "film",
     "`filter.radius`",
     {"number in [0.5, 8]", "0.5 box, 1.5 gaussian (σ = r/3), 2 Blackman-Harris",
      "filter radius, pixels"}},
    {"film",
     "output",
     FieldUse::output,
     "film",
     "`output`",
     {"path", "none", "the EXR written when `-o` is not given"}},
    {"film",
     "preview",
     FieldUse::output,
     "film",
     "`preview`",
     {"path", "none", "a PNG or JPEG preview written when `--preview` is not given"}},
    {"film",
     "pixel_type",
     FieldUse::value,
     "film",
     "`pixel_type`",
     {"`\"half\"` | `\"float\"`", "`\"half\"`",
      "storage of the colour layers of the EXR (depth, ids and shader layers are always "
      "float)"}},
    {"film",
     "view",
     FieldUse::value,
     "film",
     "`view`",
     {"string", "`\"Standard\"`",
      "the OpenColorIO view of the preview (`Standard`, `Filmic`, `Raw` in pelage's own "
      "config)"}},
    {"film",
     "layers",
     FieldUse::value,
     "film",
     "`layers`",
     {"object", "all written",
      "per AOV layer (`albedo`, `N`, `depth`, `id`, `shader`): `\"half\"`, `\"float\"` "
      "or `false` (not written); `id` and `shader` refuse `\"half\"`"}},
    {"film",
     "compression",
     FieldUse::value,
     "film",
     "`compression`",
     {"`\"none\"` | `\"rle\"` | `\"zips\"` | `\"zip\"` | `\"piz\"` | `\"pxr24\"` | "
      "`\"b44\"` | `\"b44a\"` | `\"dwaa\"` | `\"dwab\"`",
      "`\"zip\"`", "the EXR's compression"}},
    {"film",
     "cryptomatte",
     FieldUse::value,
     "film",
     "`cryptomatte`",
     {"`true` | `false` | list", "`false`",
      "Cryptomatte layers: `true` for all the materials offer, or a list of "
      "`\"object\"`, `\"type\"`, `\"cell\"`, `\"lineage\"`"}},
    {"film",
     "cryptomatte_ranks",
     FieldUse::value,
     "film",
     "`cryptomatte_ranks`",
     {"integer in [1, 16]", "6", "(id, coverage) pairs per pixel and layer"}},
    {"lights",
     "type",
     FieldUse::value,
     "lights",
     "`type`",
     {"`\"environment\"` | `\"distant\"` | `\"sphere\"` | `\"quad\"`", "required", ""}},
    {"lights", "colour", FieldUse::value, "lights", "`colour`", {"colour ≥ 0", "1", ""}},
    {"lights",
     "intensity",
     FieldUse::value,
     "lights",
     "`intensity`",
     {"number ≥ 0", "1",
      "radiance = `colour` × `intensity` (irradiance for a distant light)"}},
    {"objects",
     "name",
     FieldUse::value,
     "objects",
     "`name`",
     {"string", "`\"objectN\"`", "used by turntables and error messages"}},
    {"objects",
     "mesh",
     FieldUse::input,
     "objects",
     "`mesh`",
     {"path, `path#object` or `procedural:` name", "required", "the surface (below)"}},
    {"objects",
     "transform",
     FieldUse::value,
     "objects",
     "`transform`",
     {"object", "identity", "placement in the scene (below)"}},
    {"objects",
     "normals",
     FieldUse::value,
     "objects",
     "`normals`",
     {"`\"auto\"` | `\"smooth\"` | `\"flat\"`", "`\"auto\"`",
      "shading normals: the mesh file's vertex normals when it has them (`auto`), "
      "area-weighted vertex normals (`smooth`), or the face normal (`flat`)"}},
    {"objects",
     "cells",
     FieldUse::input,
     "objects",
     "`cells`",
     {"path", "none",
      "the object's `.cells` file from `pelage sim` (grown on this mesh or another of "
      "its shape), handed to its shader plugin (required by `clonal_mosaic`)"}},
    {"objects",
     "pattern",
     FieldUse::value,
     "objects",
     "`pattern`",
     {"object", "none",
      "how `cells` is grown: `{\"preset\": NAME or file, \"seed\": N}` (seed default 1; "
      "a preset file is relative to the scene). `pelage render`, `compare` and `bench` "
      "grow the pattern into `cells` when that file is missing or was grown from another "
      "preset (by content), seed or mesh (by content), and use it as it is otherwise; "
      "the log says which. Needs `cells`."}},
    {"objects",
     "material",
     FieldUse::value,
     "objects",
     "`material`",
     {"object", "diffuse grey", "below"}},
    {"objects",
     "fur",
     FieldUse::value,
     "objects",
     "`fur`",
     {"object", "none", "strands grown on the object, see [fur.md](fur.md)"}},
    {"objects",
     "deform",
     FieldUse::input,
     "objects",
     "`deform`",
     {"path or array of paths", "none", "deformed poses (below)"}},
    {"objects",
     "grow",
     FieldUse::value,
     "objects",
     "`grow`",
     {"object", "none",
      "the mesh at an age of a preset's `growth` block, `{\"preset\", \"from\", \"to\"}` "
      "(below)"}},
    {"objects",
     "animation",
     FieldUse::value,
     "objects",
     "`animation`",
     {"object", "none",
      "a clip of the mesh file played on the object, `{\"clip\", \"fps\", \"loop\", "
      "\"start\"}` (below)"}},
    {"objects.transform",
     "scale",
     FieldUse::value,
     "transform",
     "`scale`",
     {"number > 0, or vector", "uniform or per-axis scale", ""}},
    {"objects.transform",
     "rotate",
     FieldUse::value,
     "transform",
     "`rotate`",
     {"`[degrees, ax, ay, az]`", "rotation about the axis (ax, ay, az)", ""}},
    {"objects.transform",
     "translate",
     FieldUse::value,
     "transform",
     "`translate`",
     {"vector", "", ""}},
    {"objects.transform",
     "matrix",
     FieldUse::value,
     "transform",
     "`matrix`",
     {"12 numbers", "a row-major 3×4 affine matrix; conflicts with the three above", ""}},
    {"objects.material",
     "shader",
     FieldUse::value,
     "material",
     "`shader`",
     {"plugin name", "`\"diffuse\"`",
      "the plugin that gives the albedo (and pigments, AOVs, coat overrides) at each "
      "hit; `pelage shaders` lists the installed ones"}},
    {"objects.material",
     "params",
     FieldUse::value,
     "material",
     "`params`",
     {"object", "`{}`",
      "the plugin's parameters, checked against its table (unknown names, types, "
      "ranges); `pelage shaders NAME` prints the table"}},
    {"objects.material",
     "bsdf",
     FieldUse::value,
     "material",
     "`bsdf`",
     {"`\"lambert\"` | `\"coated\"`", "`\"lambert\"`", "the scattering model"}},
    {"objects.material",
     "roughness",
     FieldUse::value,
     "material",
     "`roughness`",
     {"number in [0, 1]", "0.3", "`coated` only: the coat's GGX roughness"}},
    {"objects.material",
     "ior",
     FieldUse::value,
     "material",
     "`ior`",
     {"number in [1, 3]", "1.5", "`coated` only: the coat's index of refraction"}},
    {"integrator",
     "max_depth",
     FieldUse::value,
     "integrator",
     "`max_depth`",
     {"integer in [1, 1024]", "8", "scattering events per path; 1 = direct light only"}},
    {"integrator",
     "rr_depth",
     FieldUse::value,
     "integrator",
     "`rr_depth`",
     {"integer in [1, 1024]", "3", "Russian roulette from this depth on"}},
    {"integrator",
     "light_selection",
     FieldUse::value,
     "integrator",
     "`light_selection`",
     {"`\"auto\"` | `\"all\"` | `\"power\"` | `\"uniform\"`", "`\"auto\"`",
      "which lights next-event estimation samples at a vertex: every one (`all`; what "
      "`auto` does for up to 4 lights), or one chosen by power or uniformly (`auto` "
      "above 4)"}},
    {"integrator",
     "clamp_indirect",
     FieldUse::value,
     "integrator",
     "`clamp_indirect`",
     {"number ≥ 0", "0",
      "firefly clamping, off at 0: the light a sample gathers beyond direct light at its "
      "first hit is scaled down to at most this in its brightest channel. It removes "
      "fireflies but darkens (biased); the EXR records `pelage:clamp_indirect`"}},
    {"integrator",
     "fur_far_field",
     FieldUse::value,
     "integrator",
     "`fur_far_field`",
     {"boolean", "true",
      "strands narrower than a pixel, and every strand a bounce reaches, are shaded with "
      "the hair model averaged over the fibre's width (the far field): the same mean "
      "image with about half the noise. `false`: each hit with the near-field model at "
      "its own offset across the fibre (the full-detail reference)"}},
    {"integrator",
     "fur_bounce_roughness",
     FieldUse::value,
     "integrator",
     "`fur_bounce_roughness`",
     {"number in [0, 1]", "0.4",
      "path regularisation of fur: a strand that a bounce (not the camera) reaches "
      "scatters with its `beta_m` and `beta_n` raised to at least this, which cuts the "
      "noise of light that strand after strand passes on, at a mean within 1 % on the "
      "bench cow. 0: every strand scatters with its own roughness (the unbiased "
      "reference)"}},
    {"integrator",
     "sampler",
     FieldUse::value,
     "integrator",
     "`sampler`",
     {"`\"sobol\"` | `\"independent\"`", "`\"sobol\"`",
      "the random numbers: Owen-scrambled Sobol points, stratified over each pixel's "
      "samples (use a power of two for `spp`), or independent white noise (for "
      "comparison)"}},
    {"animation",
     "frames",
     FieldUse::value,
     "animation",
     "`frames`",
     {"integer in [1, 10⁶]", "1", "frame count"}},
    {"animation",
     "first_frame",
     FieldUse::value,
     "animation",
     "`first_frame`",
     {"integer in [0, 10⁸]", "0",
      "the number of the first frame: the frames are `first_frame` … `first_frame + "
      "frames − 1` (1001 … 1120 as VFX numbers them); motion, poses and the sampler use "
      "*f* − `first_frame`, so renumbering changes no pixel"}},
    {"animation",
     "fps",
     FieldUse::value,
     "animation",
     "`fps`",
     {"number", "24", "frame rate, recorded in every frame and used by `pelage movie`"}},
    {"animation.turntable",
     "axis",
     FieldUse::value,
     "animation",
     "`turntable.axis`",
     {"vector", "`[0, 1, 0]`", "the axis of the turn"}},
    {"animation.turntable",
     "center",
     FieldUse::value,
     "animation",
     "`turntable.center`",
     {"vector", "`[0, 0, 0]`", "a point on the axis"}},
    {"animation.turntable",
     "degrees",
     FieldUse::value,
     "animation",
     "`turntable.degrees`",
     {"number in [−36000, 36000]", "360",
      "the turn over the whole animation: frame *f* is at `degrees` × (*f* − "
      "`first_frame`) / `frames` (a 360° loop does not repeat frame 0)"}},
    {"animation.turntable",
     "target",
     FieldUse::value,
     "animation",
     "`turntable.target`",
     {"`\"camera\"` | `\"object\"`", "`\"camera\"`",
      "orbit the camera (the scene appears to turn the other way), or turn objects"}},
    {"animation.turntable",
     "objects",
     FieldUse::value,
     "animation",
     "`turntable.objects`",
     {"array of object names", "all", "object target only: the objects that turn"}},
    {"animation",
     "shutter",
     FieldUse::value,
     "animation",
     "`shutter`",
     {"`[open, close]` within [0, 1]", "`[0, 0]`",
      "motion blur over this part of each frame: the camera of a camera turntable and "
      "every object playing a clip move during it (below)"}},
    {"animation",
     "motion_steps",
     FieldUse::value,
     "animation",
     "`motion_steps`",
     {"integer in [2, 129]", "2",
      "the times in the shutter a clip's object is posed at (evenly spaced, open to "
      "close); it moves linearly between them"}},
    {"animation.turntable",
     "shutter",
     FieldUse::value,
     "animation",
     "`turntable.shutter`",
     {"`[open, close]` within [0, 1]", "`[0, 0]`",
      "the older spelling of `shutter`, camera target only; giving both is an error"}},
    // docs/guide/fur.md
    {"objects.fur",
     "density",
     FieldUse::value,
     "fur",
     "`density`",
     {"20000 / *r*²", "≥ 0",
      "strands per unit area, in world units (after the object's transform)"}},
    {"objects.fur",
     "density_by_type",
     FieldUse::value,
     "fur",
     "`density_by_type`",
     {"all 1", "1–16 numbers in [0, 1000], not all 0",
      "multiplier per cell type, in the preset's type order (e.g. darker cells denser); "
      "see [A groom](#a-groom-by-cell-type-and-body-region) for the other keys'"}},
    {"objects.fur",
     "length",
     FieldUse::value,
     "fur",
     "`length`",
     {"0.05 *r*", "> 0", "strand length, world units"}},
    {"objects.fur",
     "length_by_type",
     FieldUse::value,
     "fur",
     "`length_by_type`",
     {"all 1", "1–16 numbers in [0, 1000]", "length multiplier per cell type"}},
    {"objects.fur",
     "length_variation",
     FieldUse::value,
     "fur",
     "`length_variation`",
     {"0.2", "[0, 0.99]", "each strand's length × U[1 − v, 1 + v]"}},
    {"objects.fur",
     "root_radius",
     FieldUse::value,
     "fur",
     "`root_radius`, `tip_radius`",
     {"0.0015 *r*, 0.0003 *r*", "> 0", "radius, linear from root to tip"}},
    {"objects.fur", "tip_radius", FieldUse::value, "fur"},
    {"objects.fur",
     "segments",
     FieldUse::value,
     "fur",
     "`segments`",
     {"8", "1–64 (round: ≥ 2)", "curve segments per strand"}},
    {"objects.fur",
     "comb",
     FieldUse::value,
     "fur",
     "`comb`",
     {"`[0, -1, 0]`", "non-zero vector, `\"normal\"`, `\"field\"`, or a field object",
      "the direction strands lie along, projected onto each root's tangent plane: a "
      "vector in the object's space (it turns with the object); `\"normal\"` makes "
      "strands stand up; `\"field\"` follows the anisotropy field the object's pattern "
      "was grown with (its preset's, e.g. `zebra`, as its `.cells` file records it; a "
      "file from an older pelage is grown again with `pelage sim`); an object as a "
      "preset's `simulation.anisotropy.field` takes it — `{\"along\": \"body_axis\"}`, "
      "`{\"around\": \"body_axis\"}`, `{\"controls\": [...]}` "
      "([growth-and-control.md](growth-and-control.md)) — resolved on the object's mesh "
      "by the simulation's own code and blended between the triangles at each vertex, so "
      "the comb is continuous"}},
    {"objects.fur",
     "comb_towards",
     FieldUse::value,
     "fur",
     "`comb_towards`",
     {"`[0, -1, 0]`", "non-zero vector",
      "a field's sense, in the object's space: a field is an axis (the cells' anisotropy "
      "has none), hair has one. Where the field lies within 60° of this line the hair "
      "points along it; elsewhere (across the spine, around a leg) it keeps its "
      "neighbours' sense, so the coat parts only where it must"}},
    {"objects.fur",
     "comb_smoothing",
     FieldUse::value,
     "fur",
     "`comb_smoothing`",
     {"0", "0–1000",
      "passes of averaging each vertex's comb direction with its neighbours' (a field "
      "rough from triangle to triangle; a smoothed comb strays from the field)"}},
    {"objects.fur",
     "comb_angle",
     FieldUse::value,
     "fur",
     "`comb_angle`",
     {"30", "[0, 90] degrees", "angle between the root direction and the surface"}},
    {"objects.fur",
     "comb_jitter",
     FieldUse::value,
     "fur",
     "`comb_jitter`",
     {"8", "[0, 60] degrees", "random tilt of each root direction"}},
    {"objects.fur",
     "gravity",
     FieldUse::value,
     "fur",
     "`gravity`",
     {"0", "[0, 10]", "downward bend (world −y) over the strand; about 1 is strong"}},
    {"objects.fur",
     "curl_radius",
     FieldUse::value,
     "fur",
     "`curl_radius`",
     {"0", "[0, 1]", "helix radius as a fraction of the length"}},
    {"objects.fur",
     "curl_turns",
     FieldUse::value,
     "fur",
     "`curl_turns`",
     {"0", "[0, 100]", "helix turns over the strand"}},
    {"objects.fur",
     "clump",
     FieldUse::value,
     "fur",
     "`clump`",
     {"0", "[0, 1]",
      "pull of each strand towards its nearest guide strand, growing to this value at "
      "the tip"}},
    {"objects.fur",
     "clump_radius",
     FieldUse::value,
     "fur",
     "`clump_radius`",
     {"0.01 *r*", "> 0", "guide spacing: one guide per π·r² of skin"}},
    {"objects.fur",
     "colour",
     FieldUse::value,
     "fur",
     "`colour`",
     {"`\"skin\"`", "`\"skin\"`, `\"skin_melanin\"`, or `[r, g, b]` each in (0, 1]",
      "the coat's hair colour: the colour the skin shows under each root (its cell "
      "type's colour after the scene's `types` and `jitter`), the skin's eumelanin and "
      "pheomelanin, or one colour for every strand (below)"}},
    {"objects.fur",
     "colour_by_type",
     FieldUse::value,
     "fur",
     "`colour_by_type`",
     {"the coat's", "1–16 entries, in the preset's type order",
      "per cell type: a colour as `colour` takes, `{\"melanin\": [eu, pheo]}`, "
      "`{\"cycles_melanin\": [m, r]}` or `{\"sigma_a\": [r, g, b]}`; types past the list "
      "take the coat's"}},
    {"objects.fur",
     "melanin",
     FieldUse::value,
     "fur",
     "`melanin`",
     {"—", "`[eumelanin, pheomelanin]`, each in [0, 100]",
      "one pigment for every strand instead of a colour"}},
    {"objects.fur",
     "sigma_a",
     FieldUse::value,
     "fur",
     "`sigma_a`",
     {"—", "`[r, g, b]`, each in [0, 1000]",
      "the absorption itself, per fibre radius (Cycles' `Absorption Coefficient`), for "
      "every strand"}},
    {"objects.fur",
     "cycles_melanin",
     FieldUse::value,
     "fur",
     "`cycles_melanin`",
     {"—", "`[melanin, redness]`, melanin in [0, 1), redness in [0, 1]",
      "the same as `melanin`, given as Cycles' Principled Hair `Melanin` and `Melanin "
      "Redness` (below)"}},
    {"objects.fur",
     "melanin_scale",
     FieldUse::value,
     "fur",
     "`melanin_scale`",
     {"1", "[0, 100]",
      "multiplies every strand's absorption σ_a (for melanins, their concentrations): "
      "above 1 darker, below 1 lighter"}},
    {"objects.fur",
     "melanin_jitter",
     FieldUse::value,
     "fur",
     "`melanin_jitter`",
     {"0.1", "[0, 1]",
      "each strand's σ_a × U[1 − j, 1 + j] (melanins: each pigment independently)"}},
    {"objects.fur",
     "beta_m",
     FieldUse::value,
     "fur",
     "`beta_m`, `beta_n`",
     {"0.25, 0.3", "(0, 1]", "longitudinal and azimuthal roughness of the hair BSDF"}},
    {"objects.fur", "beta_n", FieldUse::value, "fur"},
    {"objects.fur",
     "alpha",
     FieldUse::value,
     "fur",
     "`alpha`",
     {"2", "[−44, 44] degrees", "cuticle scale tilt"}},
    {"objects.fur",
     "curve",
     FieldUse::value,
     "fur",
     "`curve`",
     {"`\"round\"`", "`\"round\"` | `\"flat\"`",
      "B-spline tubes (close-ups) or ray-facing linear ribbons (distance)"}},
    {"objects.fur",
     "min_pixel_width",
     FieldUse::value,
     "fur",
     "`min_pixel_width`",
     {"0 (off)", "[0, 16] pixels",
      "strands narrower on screen (seen from the scene's camera) are widened to this "
      "width and made partly transparent so each covers on average what it did "
      "([below](#strands-thinner-than-a-pixel)); experimental: right within 1.5 % for a "
      "widening up to 8×, far too dark for short dense fur widened 20×"}},
    {"objects.fur",
     "regions",
     FieldUse::value,
     "fur",
     "`regions`",
     {"none", "named regions, as a preset's `\"regions\"`",
      "body regions the values below may vary over ([A "
      "groom](#a-groom-by-cell-type-and-body-region))"}},
    {"objects.fur",
     "seed",
     FieldUse::value,
     "fur",
     "`seed`",
     {"1", "", "hash seed of roots, lengths and jitter"}},
    {"objects.fur",
     "max_strands",
     FieldUse::value,
     "fur",
     "`max_strands`",
     {"2·10⁷", "1 to 5·10⁷",
      "a scene that would grow more strands is refused (memory guard)"}},
    // Described in prose, not in a reference table.
    {"", "camera"},
    {"", "film"},
    {"", "lights"},
    {"", "objects"},
    {"", "integrator"},
    {"", "animation"},
    {"film.layers", "albedo"},
    {"film.layers", "N"},
    {"film.layers", "depth"},
    {"film.layers", "id"},
    {"film.layers", "shader"},
    {"lights", "image", FieldUse::input},
    {"lights", "rotation"},
    {"lights", "direction"},
    {"lights", "angle"},
    {"lights", "center"},
    {"lights", "radius"},
    {"lights", "corner"},
    {"lights", "edge_u"},
    {"lights", "edge_v"},
    {"lights", "two_sided"},
    {"objects.pattern", "preset", FieldUse::input},
    {"objects.pattern", "seed"},
    {"objects.grow", "preset", FieldUse::input},
    {"objects.grow", "from"},
    {"objects.grow", "to"},
    {"objects.animation", "clip"},
    {"objects.animation", "fps"},
    {"objects.animation", "loop"},
    {"objects.animation", "start"},
    {"animation", "turntable"},
    {"film", "filter"},
    // A groom's values per cell type (docs/guide/fur.md, "A groom by cell type and body
    // region").
    {"objects.fur", "root_radius_by_type"},
    {"objects.fur", "tip_radius_by_type"},
    {"objects.fur", "comb_angle_by_type"},
    {"objects.fur", "curl_radius_by_type"},
    {"objects.fur", "curl_turns_by_type"},
    {"objects.fur", "clump_by_type"},
    {"objects.fur", "beta_m_by_type"},
    {"objects.fur", "beta_n_by_type"},
};

// Where each reference table is, and its columns.
struct TableDoc {
    std::string_view table, page, header;
};
constexpr TableDoc pages[] = {
    {"fur", "docs/guide/fur.md", "| key | default | range | meaning |"},
    {"transform", "docs/guide/scene-format.md", "| field | type | meaning |"},
};
constexpr TableDoc scene_page{"", "docs/guide/scene-format.md",
                              "| field | type | default | meaning |"};

const TableDoc &doc_of(std::string_view table) {
    for (const TableDoc &d : pages)
        if (d.table == table) return d;
    return scene_page;
}

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

std::string scene_field_page(std::string_view table) {
    return std::string(doc_of(table).page);
}

std::string scene_fields_markdown(std::string_view table) {
    const std::string header(doc_of(table).header);
    const size_t columns = size_t(std::count(header.begin(), header.end(), '|')) - 1;
    std::string out = header + "\n|";
    for (size_t c = 0; c < columns; ++c) out += " --- |";
    out += "\n";
    for (const SceneField &f : fields) {
        if (f.table != table || f.shown.empty()) continue;
        out += "| " + cell(f.shown) + " |";
        for (size_t c = 0; c + 1 < columns; ++c)
            out += f.cells[c].empty() ? " |" : " " + cell(f.cells[c]) + " |";
        out += "\n";
    }
    return out;
}

DeclaredFields::DeclaredFields(const json &j, std::string path, std::string file)
    : JsonObjectFields(j, path, std::move(file)), m_block(scene_block_of(path)) {}

FieldUse DeclaredFields::use(const std::string &key) const {
    const SceneField *f = scene_field(m_block, key);
    return f ? f->use : FieldUse::value;
}

void DeclaredFields::asked(const std::string &key) const {
    if (!scene_field(m_block, key))
        throw std::logic_error("the scene parser reads " + join(m_block, key) +
                               ", which scene_fields.cpp does not declare");
}

std::vector<std::string> DeclaredFields::known_keys() const {
    return scene_field_keys(m_block);
}

}  // namespace pelage::renderer
