#include "renderer/scene_file/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "renderer/animation/rig.h"
#include "renderer/scene_file/scene_fields.h"
#include "renderer/scene_file/scene_fur.h"
#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"
#include "sim/growth/growth_spec.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::renderer {
namespace {

namespace fs = std::filesystem;
using json =
    nlohmann::ordered_json;  // document order: local values apply their regions in it
using sim::json_type_name;

// One object of the scene file (sim/core/json_fields.h), with paths resolved against the
// file's folder. It reads only the fields scene_fields.h declares for its block
// (DeclaredFields), and records the files its input fields name in the scene
// (SceneDesc::inputs).
class Reader : public DeclaredFields {
  public:
    Reader(const json &j, std::string path, SceneDesc &scene)
        : DeclaredFields(j, std::move(path), scene.path), m_scene(scene) {}

    // A path relative to the scene file, made absolute.
    std::string path(const std::string &key, bool required = false) {
        const std::string s = string(key, "", required);
        if (s.empty()) {
            if (has(key)) fail(field(key), "empty path");
            return s;
        }
        const std::string resolved = resolve(s);
        if (use(key) == FieldUse::input) record_input(field(key), resolved);
        return resolved;
    }
    std::string resolve(const std::string &s) const {
        const fs::path p(s);
        return p.is_absolute() ? s
                               : (fs::path(m_scene.dir) / p).lexically_normal().string();
    }
    // A mesh reference "FILE" or "FILE#OBJECT" (sim/mesh/mesh_objects.h) at `f`: the
    // file resolved (and recorded as an input), the object name kept as written (a name
    // may hold "/..").
    std::string resolve_mesh(const std::string &s, const std::string &f) {
        try {
            const sim::MeshSpec spec = sim::parse_mesh_spec(s);
            const std::string file = resolve(spec.path);
            record_input(f, file);
            return file + (spec.object.empty() ? "" : "#" + spec.object);
        } catch (const InputError &e) {
            fail(f, std::string(e.what()).substr(std::string(e.what()).find(": ") + 2));
        }
    }
    // A file the render reads, named at JSON path `f`.
    void record_input(const std::string &f, const std::string &file) {
        m_scene.inputs.push_back({f, file});
    }
    static SceneDesc &scene_of(const Reader &r) { return r.m_scene; }

  private:
    SceneDesc &m_scene;
};

CameraDesc read_camera(Reader r) {
    CameraDesc c;
    c.type = r.choice<CameraDesc::Type>("type", c.type,
                                        {{"pinhole", CameraDesc::Type::pinhole},
                                         {"thin_lens", CameraDesc::Type::thin_lens}});
    c.position = r.vec3("position", c.position);
    c.look_at = r.vec3("look_at", c.look_at);
    c.up = r.vec3("up", c.up);
    c.fov_deg = float(r.number("fov", c.fov_deg, 0.01, 179.0));
    c.aperture_radius = float(r.number("aperture_radius", 0, 0, 1e9));
    c.focus_distance = float(r.number("focus_distance", 0, 0, 1e9));
    if (c.type == CameraDesc::Type::pinhole &&
        (r.has("aperture_radius") || r.has("focus_distance")))
        r.fail(r.field(r.has("aperture_radius") ? "aperture_radius" : "focus_distance"),
               "only a thin_lens camera has an aperture (set \"type\": \"thin_lens\")");
    r.finish();
    const Vec3f fwd = c.look_at - c.position;
    if (length(fwd) <= 0) r.fail(r.field("look_at"), "equals the camera position");
    if (length(c.up) <= 0 || length(cross(normalize(fwd), normalize(c.up))) < 1e-6f)
        r.fail(r.field("up"), "is zero or parallel to the viewing direction");
    return c;
}

LightDesc read_light(Reader r) {
    LightDesc l;
    const std::string type = r.string("type", "", true);
    if (type == "environment")
        l.type = LightDesc::Type::environment;
    else if (type == "distant")
        l.type = LightDesc::Type::distant;
    else if (type == "sphere")
        l.type = LightDesc::Type::sphere;
    else if (type == "quad")
        l.type = LightDesc::Type::quad;
    else
        r.fail(r.field("type"), "unknown light type \"" + type +
                                    "\" (expected environment, distant, sphere or quad)");
    l.color = r.color("colour", l.color);
    l.intensity = float(r.number("intensity", l.intensity, 0, 1e12));
    switch (l.type) {
        case LightDesc::Type::environment:
            l.image = r.path("image");
            l.rotation_deg = float(r.number("rotation", 0, -360, 360));
            if (!l.image.empty() && r.has("colour"))
                r.fail(r.field("colour"),
                       "conflicts with \"image\" (scale an image with \"intensity\")");
            break;
        case LightDesc::Type::distant:
            l.direction = r.vec3("direction", l.direction, -1e30, 1e30, true);
            if (length(l.direction) <= 0)
                r.fail(r.field("direction"), "must not be zero");
            l.direction = normalize(l.direction);
            l.angle_deg = float(r.number("angle", 0, 0, 90));
            break;
        case LightDesc::Type::sphere:
            l.center = r.vec3("center", l.center, -1e30, 1e30, true);
            l.radius = float(r.number("radius", 1, 1e-9, 1e30, true));
            break;
        case LightDesc::Type::quad:
            l.corner = r.vec3("corner", l.corner, -1e30, 1e30, true);
            l.edge_u = r.vec3("edge_u", l.edge_u, -1e30, 1e30, true);
            l.edge_v = r.vec3("edge_v", l.edge_v, -1e30, 1e30, true);
            l.two_sided = r.boolean("two_sided", false);
            if (!(length(cross(l.edge_u, l.edge_v)) > 0))
                r.fail(r.field("edge_v"), "edge_u and edge_v span no area");
            break;
    }
    r.finish();
    return l;
}

Affine read_transform(Reader r) {
    Affine m;
    if (r.has("matrix")) {
        for (const char *k : {"translate", "rotate", "scale"})
            if (r.has(k)) r.fail(r.field(k), "conflicts with \"matrix\"");
        const json &v = *r.take("matrix");
        if (!v.is_array() || v.size() != 12)
            r.fail(r.field("matrix"), "expected 12 numbers (a row-major 3x4 matrix)");
        for (int i = 0; i < 12; ++i)
            m.m[i / 4][i % 4] = float(r.check_number(
                v[i], r.field("matrix") + "[" + std::to_string(i) + "]", -1e30, 1e30));
    } else {
        Vec3f s{1, 1, 1};
        if (const json *sv = r.take("scale")) {
            if (sv->is_number()) {
                const float x = float(r.check_number(*sv, r.field("scale"), 1e-30, 1e30));
                s = {x, x, x};
            } else {
                s = r.check_vec3(*sv, r.field("scale"), -1e30, 1e30);
            }
        }
        Affine sm;
        sm.m[0][0] = s.x;
        sm.m[1][1] = s.y;
        sm.m[2][2] = s.z;
        Affine rm;
        if (const json *rv = r.take("rotate")) {
            // [angle in degrees, axis x, y, z]
            if (!rv->is_array() || rv->size() != 4)
                r.fail(r.field("rotate"),
                       "expected [angle_degrees, axis_x, axis_y, axis_z]");
            float a[4];
            for (int i = 0; i < 4; ++i)
                a[i] = float(r.check_number(
                    (*rv)[i], r.field("rotate") + "[" + std::to_string(i) + "]", -1e30,
                    1e30));
            Vec3f axis{a[1], a[2], a[3]};
            if (length(axis) <= 0) r.fail(r.field("rotate"), "zero rotation axis");
            axis = normalize(axis);
            const float th = a[0] * pi / 180, c = std::cos(th), sn = std::sin(th),
                        t = 1 - c;
            const float x = axis.x, y = axis.y, z = axis.z;
            const float rot[3][3] = {
                {t * x * x + c, t * x * y - sn * z, t * x * z + sn * y},
                {t * x * y + sn * z, t * y * y + c, t * y * z - sn * x},
                {t * x * z - sn * y, t * y * z + sn * x, t * z * z + c}};
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) rm.m[i][j] = rot[i][j];
        }
        const Vec3f tr = r.vec3("translate", {});
        Affine tm;
        tm.m[0][3] = tr.x;
        tm.m[1][3] = tr.y;
        tm.m[2][3] = tr.z;
        m = tm * (rm * sm);
    }
    r.finish();
    if (!(std::abs(m.determinant3()) > 1e-30f))
        r.fail(r.path_prefix(), "singular transform");
    return m;
}

MaterialDesc read_material(Reader r) {
    MaterialDesc m;
    m.shader = r.string("shader", m.shader);
    if (m.shader.empty()) r.fail(r.field("shader"), "empty shader name");
    if (const json *p = r.take("params")) {
        if (!p->is_object())
            r.fail(r.field("params"),
                   std::string("expected an object, got ") + json_type_name(*p));
        m.params = nlohmann::json(*p);
    }
    m.bsdf = r.choice<MaterialDesc::Bsdf>("bsdf", m.bsdf,
                                          {{"lambert", MaterialDesc::Bsdf::lambert},
                                           {"coated", MaterialDesc::Bsdf::coated}});
    if (m.bsdf == MaterialDesc::Bsdf::lambert && (r.has("roughness") || r.has("ior")))
        r.fail(r.field(r.has("roughness") ? "roughness" : "ior"),
               "only the \"coated\" bsdf has a coat (set \"bsdf\": \"coated\")");
    m.roughness = float(r.number("roughness", m.roughness, 0, 1));
    m.ior = float(r.number("ior", m.ior, 1.0, 3.0));
    r.finish();
    return m;
}

// "shutter": [open, close] in frames, within [0, 1].
std::pair<float, float> read_shutter(Reader &r, const json &v) {
    const std::string f = r.field("shutter");
    if (!v.is_array() || v.size() != 2)
        r.fail(f, "expected [open, close] in frames, within [0, 1]");
    const float open = float(r.check_number(v[0], f + "[0]", 0, 1));
    const float close = float(r.check_number(v[1], f + "[1]", 0, 1));
    if (close < open) r.fail(f + "[1]", "the shutter closes before it opens");
    return {open, close};
}

TurntableDesc read_turntable(Reader r) {
    TurntableDesc t;
    t.axis = r.vec3("axis", t.axis);
    if (!(length(t.axis) > 0)) r.fail(r.field("axis"), "must not be zero");
    t.axis = normalize(t.axis);
    t.center = r.vec3("center", t.center);
    t.degrees = float(r.number("degrees", t.degrees, -36000, 36000));
    t.target =
        r.choice<TurntableDesc::Target>("target", t.target,
                                        {{"camera", TurntableDesc::Target::camera},
                                         {"object", TurntableDesc::Target::object}});
    if (const json *v = r.take("objects")) {
        const std::string f = r.field("objects");
        if (t.target != TurntableDesc::Target::object)
            r.fail(f,
                   "only an object turntable turns objects (set \"target\": \"object\")");
        if (!v->is_array() || v->empty())
            r.fail(f, "expected a non-empty array of object names");
        for (size_t i = 0; i < v->size(); ++i) {
            if (!(*v)[i].is_string())
                r.fail(f + "[" + std::to_string(i) + "]",
                       std::string("expected an object name, got ") +
                           json_type_name((*v)[i]));
            t.objects.push_back((*v)[i].get<std::string>());
        }
    }
    if (const json *v = r.take("shutter")) {
        const auto [open, close] = read_shutter(r, *v);
        t.shutter_open = open;
        t.shutter_close = close;
        if (t.motion_blur() && t.target == TurntableDesc::Target::object)
            r.fail(r.field("shutter"),
                   "an object turntable is not motion-blurred: it takes no open shutter "
                   "(use \"target\": \"camera\")");
    }
    r.finish();
    return t;
}

AnimationDesc read_animation(Reader r) {
    AnimationDesc a;
    a.present = true;
    a.frames = r.integer("frames", a.frames, 1, 1000000);
    a.first_frame = r.integer("first_frame", a.first_frame, 0, 100000000);
    a.fps = r.number("fps", a.fps, 0.001, 1000);
    if (const json *v = r.take("turntable"))
        a.turntable =
            read_turntable(Reader(*v, r.field("turntable"), Reader::scene_of(r)));
    if (const json *v = r.take("shutter")) {
        if (a.turntable && a.turntable->motion_blur())
            r.fail(
                r.field("shutter"),
                "the shutter is given twice: drop turntable.shutter (animation.shutter "
                "blurs the camera turntable too)");
        std::tie(a.shutter_open, a.shutter_close) = read_shutter(r, *v);
        if (a.motion_blur() && a.turntable &&
            a.turntable->target == TurntableDesc::Target::object)
            r.fail(r.field("shutter"),
                   "an object turntable is not motion-blurred: it takes no open shutter "
                   "(use \"target\": \"camera\")");
    } else if (a.turntable) {
        a.shutter_open = a.turntable->shutter_open;
        a.shutter_close = a.turntable->shutter_close;
    }
    a.motion_steps = r.integer("motion_steps", a.motion_steps, 2, 129);
    r.finish();
    return a;
}

// "pattern": {"preset": NAME or file, "seed": N}, grown into the object's "cells" file.
PatternDesc read_pattern(Reader &object, const json &v, const std::string &cells) {
    const std::string f = object.field("pattern");
    if (cells.empty())
        object.fail(f,
                    "needs \"cells\": the file the pattern is grown into (e.g. "
                    "\"cells\": \"coat.cells\", next to the scene)");
    Reader r(v, f, Reader::scene_of(object));
    PatternDesc p;
    p.preset = r.string("preset", "", true);
    if (p.preset.empty()) r.fail(r.field("preset"), "empty preset name");
    // A preset file is found next to the scene; a name is one of pelage's presets.
    if (p.preset.find('/') != std::string::npos ||
        (p.preset.size() > 5 && p.preset.substr(p.preset.size() - 5) == ".json")) {
        p.preset = r.resolve(p.preset);
        r.record_input(r.field("preset"), p.preset);
    }
    p.seed = r.unsigned_integer("seed", p.seed, 0, UINT64_MAX);
    r.finish();
    return p;
}

ObjectDesc read_object(Reader r, size_t index) {
    ObjectDesc o;
    o.name = r.string("name", "object" + std::to_string(index));
    const std::string mesh = r.string("mesh", "", true);
    if (mesh.empty()) r.fail(r.field("mesh"), "empty mesh path");
    o.mesh =
        mesh.rfind("procedural:", 0) == 0 ? mesh : r.resolve_mesh(mesh, r.field("mesh"));
    o.cells = r.path("cells");
    if (const json *v = r.take("pattern")) o.pattern = read_pattern(r, *v, o.cells);
    o.normals = r.choice<ObjectDesc::Normals>("normals", o.normals,
                                              {{"auto", ObjectDesc::Normals::automatic},
                                               {"flat", ObjectDesc::Normals::flat},
                                               {"smooth", ObjectDesc::Normals::smooth}});
    // "deform": "pose.obj" or ["frame0.obj", "frame1.obj", ...]
    if (const json *v = r.take("deform")) {
        const std::string f = r.field("deform");
        auto one = [&](const json &e, const std::string &ef) {
            if (!e.is_string() || e.get<std::string>().empty())
                r.fail(ef, std::string("expected a mesh path, got ") +
                               (e.is_string() ? "an empty string" : json_type_name(e)));
            o.deform.push_back(r.resolve_mesh(e.get<std::string>(), ef));
        };
        if (v->is_array()) {
            if (v->empty()) r.fail(f, "empty list of meshes");
            for (size_t i = 0; i < v->size(); ++i)
                one((*v)[i], f + "[" + std::to_string(i) + "]");
        } else {
            one(*v, f);
        }
        if (o.mesh.rfind("procedural:", 0) == 0)
            r.fail(f, "a procedural mesh cannot deform (give the rest pose as a file)");
        o.deform_mesh = o.deform.back();
        o.deform_weight = 1;
    }
    // "grow": {"preset": "growing.json", "from": AGE, "to": AGE}
    if (const json *v = r.take("grow")) {
        const std::string f = r.field("grow");
        Reader g(*v, f, Reader::scene_of(r));
        ObjectDesc::Grow d;
        const bool own = g.has("preset");
        d.preset =
            own ? g.string("preset", "", true) : (o.pattern ? o.pattern->preset : "");
        if (d.preset.empty() ||
            (!own && d.preset.find('/') == std::string::npos))  // a built-in name
            g.fail(g.field("preset"),
                   "missing: the preset file whose growth block shapes the mesh (the "
                   "pattern's preset when that is a file)");
        if (own) {
            d.preset = g.resolve(d.preset);
            g.record_input(g.field("preset"), d.preset);
        }
        d.from = g.number("from", 0, -1e12, 1e12, true);
        d.to = g.number("to", 0, -1e12, 1e12, true);
        g.finish();
        if (o.mesh.rfind("procedural:", 0) == 0)
            r.fail(f, "a procedural mesh cannot grow (give the rest mesh as a file)");
        if (!o.deform.empty()) r.fail(f, "grow and deform cannot be combined");
        sim::load_growth(d.preset);  // its errors before any rendering
        o.grow = d;
        o.grow_age = d.to;
    }
    // "animation": {"clip": NAME, "fps": 24, "loop": true, "start": SECONDS}
    if (const json *v = r.take("animation")) {
        const std::string f = r.field("animation");
        Reader a(*v, f, Reader::scene_of(r));
        ObjectDesc::Clip c;
        c.name = a.string("clip", "", true);
        c.fps = a.number("fps", 0, 0.001, 1000);
        c.loop = a.boolean("loop", true);
        c.start = a.number("start", 0, -1e9, 1e9);
        a.finish();
        if (o.mesh.rfind("procedural:", 0) == 0)
            r.fail(f, "a procedural mesh has no clips (give a glTF, FBX, ... file)");
        if (!o.deform.empty() || o.grow)
            r.fail(f, "a clip cannot be combined with \"deform\" or \"grow\"");
        // The file's errors (no clips, a broken skin) and the clip's name, before any
        // rendering.
        const Rig rig = Rig::read(o.mesh);
        const int clip = rig.clip(c.name, f + ".clip");
        if (!rig.moves_mesh(clip))
            a.fail(a.field("clip"), "clip \"" + c.name + "\" of " + o.mesh +
                                        " moves nothing of this mesh (no bone, node or "
                                        "morph weight of it is animated)");
        c.duration = rig.duration_seconds(clip);
        o.clip = c;
        o.clip_seconds = clip_time(c.start, c.duration, c.loop);
    }
    if (const json *v = r.take("fur"))
        o.fur = read_fur(*v, r.field("fur"), Reader::scene_of(r).path);
    r.finish();
    return o;
}

// How deeply arrays and objects nest in JSON text (brackets inside strings not
// counted), without building anything.
size_t nesting_depth(const std::string &text) {
    size_t depth = 0, deepest = 0;
    bool in_string = false, escaped = false;
    for (const char ch : text) {
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (ch == '\\')
                escaped = true;
            else if (ch == '"')
                in_string = false;
        } else if (ch == '"') {
            in_string = true;
        } else if (ch == '[' || ch == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((ch == ']' || ch == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

// The JSON document, or an InputError with the line of a syntax error.
json parse_json(const std::string &text, const std::string &path) {
    // nlohmann's ordered_json copies each finished member into its object while parsing,
    // recursively: JSON nested tens of thousands deep would overflow the stack. No scene
    // nests beyond a handful of levels; valid JSON nested past this is refused.
    constexpr size_t max_depth = 512;
    if (const size_t d = nesting_depth(text); d > max_depth && json::accept(text))
        throw InputError(path, 0, "",
                         "nested " + std::to_string(d) +
                             " levels deep (a scene nests at most " +
                             std::to_string(max_depth) + ")");
    try {
        return json::parse(text);
    } catch (const json::parse_error &e) {
        // nlohmann reports a byte offset; turn it into a line number.
        const size_t at = std::min<size_t>(e.byte, text.size());
        const size_t line = 1 + std::count(text.begin(), text.begin() + long(at), '\n');
        std::string what = e.what();
        const auto pos = what.find("parse error");
        throw InputError(
            path, line, "",
            "invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos)));
    } catch (const json::exception &e) {
        // out_of_range: a number such as 1e400 that overflows a double.
        throw InputError(path, 0, "", std::string("invalid JSON: ") + e.what());
    }
}

// film.layers, film.compression, film.cryptomatte and film.cryptomatte_ranks.
void read_film_layers(Reader &fr, SceneDesc &scene, FilmDesc *f) {
    using LT = FilmDesc::LayerType;
    const LT colour = f->half ? LT::half : LT::single;
    f->albedo = f->normal = colour;
    if (const json *lv = fr.take("layers")) {
        if (!lv->is_object())
            fr.fail(fr.field("layers"),
                    std::string("expected an object such as {\"depth\": "
                                "false}, got ") +
                        json_type_name(*lv));
        Reader lr(*lv, "film.layers", scene);
        // "half", "float", or false (not written).
        auto layer = [&](const char *key, LT def, bool exact) {
            const json *v = lr.take(key);
            if (!v) return def;
            if (v->is_boolean() && !v->get<bool>()) return LT::off;
            if (v->is_string() && v->get<std::string>() == "float") return LT::single;
            if (v->is_string() && v->get<std::string>() == "half") {
                if (exact)
                    lr.fail(lr.field(key),
                            "\"half\" cannot hold ids above 2048 exactly: use "
                            "\"float\" or false");
                return LT::half;
            }
            lr.fail(lr.field(key),
                    "expected \"half\", \"float\" or false, got " + v->dump());
        };
        f->albedo = layer("albedo", f->albedo, false);
        f->normal = layer("N", f->normal, false);
        f->depth = layer("depth", f->depth, false);
        f->id = layer("id", f->id, true);
        f->shader = layer("shader", f->shader, true);
        lr.finish();
    }
    f->compression = fr.choice<std::string>("compression", f->compression,
                                            {{"none", "none"},
                                             {"rle", "rle"},
                                             {"zips", "zips"},
                                             {"zip", "zip"},
                                             {"piz", "piz"},
                                             {"pxr24", "pxr24"},
                                             {"b44", "b44"},
                                             {"b44a", "b44a"},
                                             {"dwaa", "dwaa"},
                                             {"dwab", "dwab"}});
    if (const json *cv = fr.take("cryptomatte")) {
        if (cv->is_boolean()) {
            // true: the object layer and every matte layer the materials offer
            // (resolved by the scene, which knows the plugins).
            if (cv->get<bool>()) f->cryptomatte = {"*"};
        } else if (cv->is_array()) {
            for (size_t i = 0; i < cv->size(); ++i) {
                const json &e = (*cv)[i];
                const std::string at = "film.cryptomatte[" + std::to_string(i) + "]";
                if (!e.is_string() || e.get<std::string>().empty())
                    fr.fail(at,
                            "expected a layer name such as \"object\", got " + e.dump());
                const std::string name = e.get<std::string>();
                if (std::find(f->cryptomatte.begin(), f->cryptomatte.end(), name) !=
                    f->cryptomatte.end())
                    fr.fail(at, "\"" + name + "\" is listed twice");
                f->cryptomatte.push_back(name);
            }
        } else {
            fr.fail(fr.field("cryptomatte"),
                    std::string("expected true, false or a list such as [\"object\", "
                                "\"type\"], got ") +
                        json_type_name(*cv));
        }
    }
    f->cryptomatte_ranks = fr.integer("cryptomatte_ranks", f->cryptomatte_ranks, 1, 16);
}

FilmDesc read_film(Reader fr, SceneDesc &scene) {
    FilmDesc f;
    f.width = fr.integer("width", f.width, 1, 65536);
    f.height = fr.integer("height", f.height, 1, 65536);
    f.spp = fr.integer("spp", f.spp, 1, 1 << 20);
    if (const json *fv = fr.take("filter")) {
        Reader flt(*fv, "film.filter", scene);
        f.filter =
            flt.choice<FilterType>("type", f.filter,
                                   {{"box", FilterType::box},
                                    {"gaussian", FilterType::gaussian},
                                    {"blackman_harris", FilterType::blackman_harris}});
        const float def = f.filter == FilterType::box
                              ? 0.5f
                              : (f.filter == FilterType::gaussian ? 1.5f : 2.0f);
        f.filter_radius = float(flt.number("radius", def, 0.5, 8));
        flt.finish();
    }
    f.output = fr.path("output");
    f.preview = fr.path("preview");
    f.half = fr.choice<bool>("pixel_type", true, {{"half", true}, {"float", false}});
    f.view = fr.string("view", f.view);
    f.noise_threshold = float(fr.number("noise_threshold", 0, 0, 1));
    f.min_spp = fr.integer("min_spp", f.min_spp, 1, 1 << 20);
    f.denoise = fr.boolean("denoise", false);
    read_film_layers(fr, scene, &f);
    fr.finish();
    return f;
}

// The "lights" array; at most one environment.
void read_lights(Reader &r, const json &v, SceneDesc *scene) {
    if (!v.is_array())
        r.fail("lights", std::string("expected an array, got ") + json_type_name(v));
    for (size_t i = 0; i < v.size(); ++i)
        scene->lights.push_back(
            read_light(Reader(v[i], "lights[" + std::to_string(i) + "]", *scene)));
    size_t environments = 0;
    for (const auto &l : scene->lights)
        environments += l.type == LightDesc::Type::environment;
    if (environments > 1) r.fail("lights", "more than one environment light");
}

// The "objects" array. The transform and material are read first, so that their errors
// come before those of the remaining keys (name, mesh, cells, normals).
void read_objects(Reader &r, SceneDesc *scene) {
    const json &objs = r.require("objects");
    if (!objs.is_array())
        r.fail("objects", std::string("expected an array, got ") + json_type_name(objs));
    for (size_t i = 0; i < objs.size(); ++i) {
        const std::string p = "objects[" + std::to_string(i) + "]";
        Reader orr(objs[i], p, *scene);
        ObjectDesc o;
        if (const json *t = orr.take("transform"))
            o.transform = read_transform(Reader(*t, p + ".transform", *scene));
        if (const json *m = orr.take("material"))
            o.material = read_material(Reader(*m, p + ".material", *scene));
        const Affine t = o.transform;
        const MaterialDesc mat = o.material;
        o = read_object(std::move(orr), i);
        o.transform = t;
        o.material = mat;
        scene->objects.push_back(std::move(o));
    }
}

// What the animation names must exist: turntable objects, per-frame deform lists whose
// length is the frame count.
void check_animation(Reader &r, const SceneDesc &scene) {
    if (const auto &tt = scene.animation.turntable)
        for (size_t i = 0; i < tt->objects.size(); ++i)
            if (std::none_of(
                    scene.objects.begin(), scene.objects.end(),
                    [&](const ObjectDesc &o) { return o.name == tt->objects[i]; }))
                r.fail("animation.turntable.objects[" + std::to_string(i) + "]",
                       "no object is named \"" + tt->objects[i] + "\"");
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const auto &d = scene.objects[i].deform;
        if (d.size() > 1 && int(d.size()) != scene.animation.frames)
            r.fail("objects[" + std::to_string(i) + "].deform",
                   "a per-frame list of " + std::to_string(d.size()) +
                       " meshes needs animation.frames = " + std::to_string(d.size()) +
                       " (it is " + std::to_string(scene.animation.frames) + ")");
    }
}

IntegratorDesc read_integrator(Reader ir) {
    IntegratorDesc d;
    d.max_depth = ir.integer("max_depth", d.max_depth, 1, 1024);
    d.rr_depth = ir.integer("rr_depth", d.rr_depth, 1, 1024);
    d.clamp_indirect = float(ir.number("clamp_indirect", 0, 0, 1e30));
    d.fur_far_field = ir.boolean("fur_far_field", d.fur_far_field);
    d.fur_bounce_roughness =
        float(ir.number("fur_bounce_roughness", d.fur_bounce_roughness, 0, 1));
    d.light_selection = ir.choice<IntegratorDesc::LightSelection>(
        "light_selection", d.light_selection,
        {{"auto", IntegratorDesc::LightSelection::automatic},
         {"all", IntegratorDesc::LightSelection::all},
         {"power", IntegratorDesc::LightSelection::power},
         {"uniform", IntegratorDesc::LightSelection::uniform}});
    d.sampler = ir.choice<IntegratorDesc::SamplerKind>(
        "sampler", d.sampler,
        {{"sobol", IntegratorDesc::SamplerKind::sobol},
         {"independent", IntegratorDesc::SamplerKind::independent}});
    ir.finish();
    return d;
}

}  // namespace

SceneDesc parse_scene(const std::string &text, const std::string &path) {
    SceneDesc scene;
    scene.path = path;
    scene.dir = path.empty() ? fs::current_path().string()
                             : fs::absolute(fs::path(path)).parent_path().string();
    const json root = parse_json(text, path);
    Reader r(root, "", scene);
    if (const json *v = r.take("camera"))
        scene.camera = read_camera(Reader(*v, "camera", scene));
    else
        r.fail("camera", "missing required field");
    if (const json *v = r.take("film"))
        scene.film = read_film(Reader(*v, "film", scene), scene);
    if (const json *v = r.take("lights")) read_lights(r, *v, &scene);
    read_objects(r, &scene);
    if (const json *v = r.take("animation"))
        scene.animation = read_animation(Reader(*v, "animation", scene));
    check_animation(r, scene);
    if (const json *v = r.take("integrator"))
        scene.integrator = read_integrator(Reader(*v, "integrator", scene));
    r.finish();
    if (scene.objects.empty() && scene.lights.empty())
        r.fail("objects", "the scene is empty (no objects, no lights)");
    return scene;
}

SceneDesc load_scene_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open scene file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_scene(ss.str(), path);
}

}  // namespace pelage::renderer
