#include "renderer/look/look_scene.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "sim/mesh/mesh_objects.h"

namespace pelage::renderer {

std::string mesh_reference(const std::string &mesh,
                           const std::filesystem::path &scene_dir) {
    namespace fs = std::filesystem;
    if (mesh.rfind("procedural:", 0) == 0) return mesh;
    const sim::MeshSpec spec = sim::parse_mesh_spec(mesh);
    const std::string object = spec.object.empty() ? "" : "#" + spec.object;
    const fs::path abs = fs::absolute(spec.path).lexically_normal();
    const fs::path rel = abs.lexically_relative(scene_dir);
    if (!rel.empty() && *rel.begin() != "..") return rel.generic_string() + object;
    return abs.string() + object;
}

namespace {

using json = nlohmann::ordered_json;

// Six significant digits: the file reads well and the framing moves far less than a
// pixel.
double round6(double x) { return std::stod(fmt::format("{:.6g}", x)); }

json vec(Vec3f v) { return json::array({round6(v.x), round6(v.y), round6(v.z)}); }

// The ground: a plane through the object's lowest point, perpendicular to `up`, large
// enough to reach the horizon in the framed view.
json ground_object(const LookSetup &s) {
    const Framing &f = s.framing;
    const Vec3f y{0, 1, 0};
    json transform = {{"scale", round6(40 * f.radius)}};
    // procedural:plane lies in the xz-plane, facing +y: turn it to face `up`.
    const Vec3f axis = cross(y, s.up);
    const float c = dot(y, s.up);
    if (length(axis) > 1e-6f)
        transform["rotate"] = {
            round6(std::acos(std::clamp(c, -1.0f, 1.0f)) * 180 / 3.14159265358979),
            round6(axis.x), round6(axis.y), round6(axis.z)};
    else if (c < 0)
        transform["rotate"] = {180, 1, 0, 0};
    const Vec3f centre_on_ground = f.center + s.up * (f.ground - dot(f.center, s.up));
    transform["translate"] = vec(centre_on_ground);
    return {{"name", "ground"},
            {"mesh", "procedural:plane:1x1"},
            {"transform", transform},
            {"material", {{"shader", "diffuse"}, {"params", {{"albedo", 0.35}}}}}};
}

// Fur at the scale of the body: the coat of scenes/fur_cow_giraffe.json (the cow's
// bounding radius is 0.608) with every length scaled by the object's bounding radius,
// so the strand count stays near 300 000 whatever the mesh's units.
// Hair lies along the preset's anisotropy field when it has one (a zebra's along its
// stripes' field), in the sense of the ground and a little along the body, and jitters
// less than loose hair would (4° against 12°: a groom that follows a field is a tidy
// one, and two 12° jitters would hide the field between neighbours); without a field
// it lies towards the ground and a little along the body, towards the tail (the
// framing's long axis points to the head, body_facing.h), as an animal's coat lies.
json fur_block(const LookSetup &s) {
    const double k = (s.body_radius > 0 ? s.body_radius : s.framing.radius) / 0.608;
    const Vec3f comb = -s.up - s.framing.long_axis * 0.3f;
    json fur = {{"density", round6(300000 / (k * k))},
                {"density_by_type", {1.2, 1.0}},
                {"length", round6(0.012 * k)},
                {"length_variation", 0.3},
                {"root_radius", round6(0.0004 * k)},
                {"tip_radius", round6(0.0001 * k)},
                {"segments", 6},
                {"comb", s.comb_field ? json("field") : vec(comb)},
                {"comb_angle", 20},
                {"comb_jitter", s.comb_field ? 4 : 12},
                {"gravity", 0.2},
                {"clump", 0.2},
                {"clump_radius", round6(0.004 * k)},
                {"seed", s.seed}};
    if (s.comb_field) fur["comb_towards"] = vec(comb);
    return fur;
}

}  // namespace

json look_scene(const LookSetup &s) {
    const Framing &f = s.framing;
    // The sun comes from above, over the camera's left shoulder.
    const Vec3f right = normalize(cross(-f.view, s.up));
    const Vec3f towards_sun = normalize(s.up * 1.2f - right * 0.6f + f.view * 0.5f);
    json animal = {{"name", s.object_name},
                   {"mesh", s.mesh},
                   {"cells", s.cells},
                   {"pattern", {{"preset", s.preset}, {"seed", s.seed}}},
                   {"normals", "smooth"},
                   {"material",
                    {{"shader", "clonal_mosaic"},
                     {"params", {{"jitter", 0.15}}},
                     {"bsdf", "lambert"}}}};
    if (!s.clip.empty()) animal["animation"] = {{"clip", s.clip}};
    if (s.fur) animal["fur"] = fur_block(s);
    json objects = json::array({animal});
    for (const LookSetup::Prop &p : s.props) {
        json material = {{"shader", "diffuse"}, {"params", {{"albedo", 0.5}}}};
        if (p.materials) {
            material = {{"shader", "mesh_material"}};
            if (!p.textures) material["params"] = {{"textures", 0}};
        }
        json prop = {{"name", p.name}, {"mesh", p.mesh}, {"material", material}};
        if (p.animated) prop["animation"] = {{"clip", s.clip}};
        objects.push_back(prop);
    }
    if (s.ground) objects.push_back(ground_object(s));
    json scene = {
        {"camera",
         {{"type", "pinhole"},
          {"position", vec(f.camera.position)},
          {"look_at", vec(f.camera.look_at)},
          {"up", vec(f.camera.up)},
          {"fov", round6(f.camera.fov_deg)}}},
        {"film",
         {{"width", s.width},
          {"height", s.height},
          {"spp", s.spp},
          {"filter", {{"type", "gaussian"}, {"radius", 1.5}}},
          {"output", s.output},
          {"preview", s.preview},
          {"view", s.view},
          {"denoise", s.denoise}}},
        {"lights",
         {{{"type", "environment"}, {"colour", {0.55, 0.68, 0.9}}, {"intensity", 0.8}},
          {{"type", "distant"},
           {"direction", vec(-towards_sun)},
           {"angle", 0.53},
           {"colour", {1.0, 0.93, 0.82}},
           {"intensity", 4.0}}}},
        {"objects", objects},
        // A coat's light types need the bounces: light crosses several fibres and the
        // skin before it leaves, and six bounces left `look`'s light fur at 0.62–0.72 of
        // its bare skin's luminance where twelve give 0.80–1.08 (`pelage bench
        // fur-colour`), for 3 % more render time.
        {"integrator", {{"max_depth", s.fur ? 12 : 6}, {"rr_depth", 3}}}};
    if (!s.clip.empty()) {
        scene["animation"] = {{"frames", s.frames}, {"fps", s.fps}};
        if (s.shutter > 0) scene["animation"]["shutter"] = {0.0, s.shutter};
    }
    return scene;
}

namespace {

void format_into(const json &j, int indent, std::string *out) {
    const std::string pad(size_t(indent) + 2, ' ');
    if (j.is_object() && !j.empty()) {
        *out += "{\n";
        size_t i = 0;
        for (const auto &[key, value] : j.items()) {
            *out += pad + json(key).dump() + ": ";
            format_into(value, indent + 2, out);
            *out += ++i < j.size() ? ",\n" : "\n";
        }
        *out += std::string(size_t(indent), ' ') + "}";
    } else if (j.is_array() && !j.empty() &&
               std::any_of(j.begin(), j.end(),
                           [](const json &e) { return e.is_structured(); })) {
        *out += "[\n";
        for (size_t i = 0; i < j.size(); ++i) {
            *out += pad;
            format_into(j[i], indent + 2, out);
            *out += i + 1 < j.size() ? ",\n" : "\n";
        }
        *out += std::string(size_t(indent), ' ') + "]";
    } else if (j.is_array()) {
        *out += "[";
        for (size_t i = 0; i < j.size(); ++i) *out += (i ? ", " : "") + j[i].dump();
        *out += "]";
    } else {
        *out += j.dump();
    }
}

}  // namespace

std::string format_scene_json(const json &j) {
    std::string out;
    format_into(j, 0, &out);
    return out + "\n";
}

}  // namespace pelage::renderer
