// Scene files (scenes/*.json): the description of what to render, parsed and fully
// validated before any work starts. Every field is checked (type, range); unknown keys
// are errors; errors are pelage::InputError naming the scene file and the JSON path, e.g.
// `objects[2].material.shader: unknown shader "wroley"`. Paths inside a scene are
// resolved relative to the scene file. The format is documented in
// docs/guide/scene-format.md.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/fur/fur_params.h"

namespace pelage::renderer {

struct CameraDesc {
    enum class Type { pinhole, thin_lens } type = Type::pinhole;
    Vec3f position{0, 1, 5}, look_at{0, 0, 0}, up{0, 1, 0};
    float fov_deg = 40;         // vertical field of view
    float aperture_radius = 0;  // thin lens only, scene units
    float focus_distance = 0;   // thin lens only; 0 = distance to look_at
};

enum class FilterType { box, gaussian, blackman_harris };

struct FilmDesc {
    int width = 640, height = 360, spp = 16;
    FilterType filter = FilterType::gaussian;
    float filter_radius = 1.5f;  // pixels
    std::string output;          // absolute, "" = none given
    std::string preview;         // absolute, "" = none
    bool half = true;  // beauty/albedo/normal as half; depth/ids/shader always float
    std::string view = "Standard";  // OCIO view of the preview
    // Adaptive sampling (renderer/integrator/render.h): a pixel stops once its noise
    // estimate is below this; 0 = every pixel takes spp samples.
    float noise_threshold = 0;
    int min_spp = 16;  // ... but never before this many samples
    // Denoise the beauty (renderer/denoise): the EXR adds it as the `denoised` layer and
    // the preview shows it.
    bool denoise = false;
    // The EXR's layers beyond the beauty (docs/guide/compositing-outputs.md): each
    // written as half or float, or not at all. Colour layers default to `half`'s type;
    // depth, ids and the shader's values to float (ids are not exact in half).
    enum class LayerType { off, half, single };
    LayerType albedo = LayerType::half, normal = LayerType::half,
              depth = LayerType::single, id = LayerType::single,
              shader = LayerType::single;
    std::string compression = "zip";  // OpenEXR's compression, as OIIO names it
    // Cryptomatte layers: "object" and the material plugins' matte layers ("type",
    // "cell", ...), each with `cryptomatte_ranks` (id, coverage) pairs per pixel.
    std::vector<std::string> cryptomatte;
    int cryptomatte_ranks = 6;
};

struct LightDesc {
    enum class Type { environment, distant, sphere, quad } type = Type::environment;
    Rgb color{1, 1, 1};
    float intensity = 1;
    std::string image;          // environment: absolute path of a lat-long image, or ""
    float rotation_deg = 0;     // environment: about +y
    Vec3f direction{0, -1, 0};  // distant: the direction light travels
    float angle_deg = 0;        // distant: apparent diameter (0.53 for the sun)
    Vec3f center{};             // sphere
    float radius = 1;           // sphere
    Vec3f corner{}, edge_u{1, 0, 0},
        edge_v{0, 0, 1};     // quad; emits towards edge_u × edge_v
    bool two_sided = false;  // quad
};

struct ParamValue {
    std::string name;
    int type = 0;  // PelageParamType
    std::array<float, 3> f{};
    int i = 0;
    std::string s;
};

struct MaterialDesc {
    std::string shader = "diffuse";
    nlohmann::json params =
        nlohmann::json::object();  // validated against the plugin later
    enum class Bsdf { lambert, coated } bsdf = Bsdf::lambert;
    float roughness = 0.3f, ior = 1.5f;
};

// How an object's cells are grown: `pelage render` grows them into the object's `cells`
// file when it is missing or was grown from another preset, seed or mesh.
struct PatternDesc {
    std::string preset;  // a preset name, or the absolute path of a preset file
    uint64_t seed = 1;
};

struct ObjectDesc {
    std::string name;
    std::string mesh;  // absolute path or "procedural:..."
    Affine transform;
    MaterialDesc material;
    std::string cells;  // absolute path or ""
    std::optional<PatternDesc> pattern;
    enum class Normals { automatic, flat, smooth } normals = Normals::automatic;
    // Deformation (same topology as `mesh`): one pose, or one mesh per animation frame.
    std::vector<std::string> deform;  // absolute paths; empty = rigid
    // The pose rendered: positions = lerp(mesh, deform_mesh, deform_weight). Set by the
    // parser (the last pose, weight 1) and by scene_at_frame().
    std::string deform_mesh;
    float deform_weight = 0;
    // "grow": the mesh grown by a preset's growth block (sim/growth/growth_spec.h) to the
    // age `from` at the first frame, `to` at the last; a still shows `to`.
    struct Grow {
        std::string preset;  // absolute path of the preset file
        double from = 0, to = 0;
    };
    std::optional<Grow> grow;
    double grow_age = 0;  // the age rendered: set by the parser (to) and scene_at_frame()
    // "animation": a clip of the mesh file (skins, morph targets, node motion;
    // renderer/animation/rig.h) played on the object. The pattern stays on the rest
    // mesh's triangles; the pose moves them.
    struct Clip {
        std::string name;
        double fps = 0;    // frames per second of the scene's frames; 0 = animation.fps
        bool loop = true;  // wrap past the clip's end, or hold its last pose
        double start = 0;  // seconds into the clip at the first frame
        double duration = 0;  // the clip's length in seconds (from the file)
    };
    std::optional<Clip> clip;
    double clip_seconds =
        0;  // the time posed: set by the parser (start), scene_at_frame()
    // With an open shutter (AnimationDesc::shutter), the clip's times at the shutter's
    // motion steps, open to close, evenly spaced (clip_seconds is the first): the
    // object moves through the shutter (Embree's time steps). Empty: sharp.
    std::vector<double> clip_motion_seconds;
    std::optional<FurParams>
        fur;  // strands on this object (renderer/scene_file/scene_fur.h)
};

// "animation": {"frames", "first_frame", "fps", "turntable": {...}}. A turntable turns
// the camera about the axis through `center` (target camera; the scene turns the other
// way in the image) or every object (target object) by `degrees` over the whole
// animation: frame f at degrees·f/frames, so a 360° loop does not repeat its first frame.
// Its shutter (an older spelling of animation.shutter) blurs the camera's motion (camera
// target only).
struct TurntableDesc {
    Vec3f axis{0, 1, 0}, center{0, 0, 0};
    float degrees = 360;
    enum class Target { camera, object } target = Target::camera;
    std::vector<std::string> objects;  // target object: the names turned ({} = all)
    float shutter_open = 0, shutter_close = 0;
    bool motion_blur() const { return shutter_close > shutter_open; }
};

// "shutter": [open, close] in frames, within [0, 1]: an open shutter blurs what moves
// during it, the camera of a camera turntable and every object playing a clip, each
// sample at a time in it. A clip's object is posed at `motion_steps` evenly spaced times
// and moves linearly between them (Embree's multi-segment motion blur).
struct AnimationDesc {
    bool present = false;
    float shutter_open = 0, shutter_close = 0;
    int motion_steps = 2;
    bool motion_blur() const { return shutter_close > shutter_open; }
    int frames = 1;
    // The number of the first frame (1001 in VFX): frames are first_frame ..
    // first_frame + frames - 1, and motion is computed from frame - first_frame.
    int first_frame = 0;
    double fps = 24;
    std::optional<TurntableDesc> turntable;
};

struct IntegratorDesc {
    int max_depth = 8;  // path vertices after the camera
    int rr_depth = 3;   // Russian roulette from this depth on
    // Firefly clamping, off at 0: the light a sample gathers after its first bounce
    // (everything but direct light at the first hit) is scaled down to at most this in
    // its brightest channel. Biased (it darkens), so recorded in the EXR.
    float clamp_indirect = 0;
    // Strand hits where the ray's offset across the fibre is uniform (sub-pixel strands
    // seen by the camera, every strand a bounce meets) take the far-field hair model
    // (HairBsdf::FarField); false: the near-field model at every hit.
    bool fur_far_field = true;
    // Path regularisation of fur (Kaplanyan & Dachsbacher 2013): a strand a bounce
    // reaches scatters with its longitudinal and azimuthal roughness raised to at least
    // this; camera hits keep their own. 0: every strand its own roughness everywhere.
    float fur_bounce_roughness = 0.4f;
    // Next-event estimation samples every light at every vertex (all; automatic for up
    // to Lights::max_sample_all lights), or picks one: in proportion to its estimated
    // power (automatic for more lights), or uniformly.
    enum class LightSelection {
        automatic,
        all,
        power,
        uniform
    } light_selection = LightSelection::automatic;
    // The sampler's numbers (renderer/core/sampler.h): stratified or white noise.
    enum class SamplerKind { sobol, independent } sampler = SamplerKind::sobol;
};

struct SceneDesc {
    std::string path;  // the scene file ("" when parsed from a string)
    std::string dir;   // its folder: relative paths resolve against it
    CameraDesc camera;
    FilmDesc film;
    std::vector<LightDesc> lights;
    std::vector<ObjectDesc> objects;
    IntegratorDesc integrator;
    AnimationDesc animation;
    // The files the scene's input fields name (scene_fields.h), in the order read: the
    // JSON path of the field and the file (a mesh reference's file, without #OBJECT).
    struct InputFile {
        std::string field, path;
    };
    std::vector<InputFile> inputs;
};

// Reads and validates a scene file. Throws pelage::InputError.
SceneDesc load_scene_file(const std::string &path);
// The same, from text; `path` names it in errors and anchors relative paths.
SceneDesc parse_scene(const std::string &text, const std::string &path);

}  // namespace pelage::renderer
