#include "renderer/scene_file/scene_fur.h"

#include <algorithm>
#include <cmath>

#include "renderer/scene_file/scene_fields.h"
#include "sim/control/control_parse.h"
#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"

namespace pelage::renderer {

namespace {

using json =
    nlohmann::ordered_json;  // document order: local values apply their regions in it
using sim::JsonObjectFields;

// A list of per-cell-type values, each in [lo, hi] ((lo, hi] when open_lo).
std::vector<float> per_type(JsonObjectFields &r, const std::string &key, double lo,
                            double hi, bool open_lo) {
    const json *v = r.take(key);
    if (!v) return {};
    if (!v->is_array() || v->empty() || v->size() > 16)
        r.fail(r.field(key), "expected an array of 1 to 16 numbers (one per cell type)");
    std::vector<float> out;
    for (size_t i = 0; i < v->size(); ++i)
        out.push_back(float(r.check_number(
            (*v)[i], r.field(key) + "[" + std::to_string(i) + "]", lo, hi, open_lo)));
    return out;
}

// A key of the groom (FurParams::Groomed): a number in its range, or a local value
// {"default": number, "in": {region: number, ...}} over the fur's regions, as presets
// give them (sim/control); and KEY_by_type, per cell type a factor in (0, 1000] for
// sizes and density ([0, 1000] for density: no hair on a type) or a value in the key's
// range otherwise. Returns the coat's value (`def` when absent).
double groomed(JsonObjectFields &r, FurParams *p, FurParams::Groomed k,
               const std::string &key, double def, sim::ValueRange range) {
    using G = FurParams::Groomed;
    const bool factor =
        k == G::length || k == G::density || k == G::root_radius || k == G::tip_radius;
    FurParams::Varying &v = p->vary(k);
    v.by_type = factor ? per_type(r, key + "_by_type", 0, 1000, k != G::density)
                       : per_type(r, key + "_by_type", range.lo, range.hi, range.lo_open);
    const json *j = r.take(key);
    if (!j) return def;
    if (!sim::is_local_value(*j))
        return r.check_number(*j, r.field(key), range.lo, range.hi, range.lo_open);
    if (p->regions.empty())
        r.fail(r.field(key),
               "a value by region needs the fur's \"regions\" (named as in a preset: "
               "{\"face\": {\"near\": ...}, ...})");
    const sim::LocalValue local =
        sim::parse_local_value(*j, r.field(key), r.file(), p->regions, range);
    for (const auto &[region, value] : local.in) v.in.push_back({region, float(value)});
    return local.value;
}

// An optional number in [lo, hi] ((lo, hi] when open_lo), as the float FurParams holds.
float num(JsonObjectFields &r, const std::string &key, float def, double lo, double hi,
          bool open_lo = false) {
    return float(r.number(key, def, lo, hi, false, open_lo));
}

// Cycles' Principled Hair: Melanin m and Melanin Redness r give concentrations q (1 − r)
// and q r with q = −ln(1 − m), times its own absorption coefficients, (0.506, 0.841,
// 1.653) and (0.343, 0.733, 1.924): 1.207 and 1.833 times d'Eon's, which
// renderer/bsdf/hair_pigments uses (within 0.1 % per channel).
FurParams::Pigment cycles_melanin(const JsonObjectFields &r, const json &v,
                                  const std::string &f) {
    if (!v.is_array() || v.size() != 2)
        r.fail(f, "expected [melanin, redness], as Cycles' Principled Hair has them");
    const double m = r.check_number(v[0], f + "[0]", 0, 0.9999);
    const double red = r.check_number(v[1], f + "[1]", 0, 1);
    const double q = -std::log(1 - m);
    FurParams::Pigment p;
    p.kind = FurParams::Pigment::Kind::melanin;
    p.eumelanin = float(1.207 * q * (1 - red));
    p.pheomelanin = float(1.833 * q * red);
    return p;
}

FurParams::Pigment melanin(const JsonObjectFields &r, const json &v,
                           const std::string &f) {
    if (!v.is_array() || v.size() != 2) r.fail(f, "expected [eumelanin, pheomelanin]");
    FurParams::Pigment p;
    p.kind = FurParams::Pigment::Kind::melanin;
    p.eumelanin = float(r.check_number(v[0], f + "[0]", 0, 100));
    p.pheomelanin = float(r.check_number(v[1], f + "[1]", 0, 100));
    return p;
}

FurParams::Pigment absorption(const JsonObjectFields &r, const json &v,
                              const std::string &f) {
    FurParams::Pigment p;
    p.kind = FurParams::Pigment::Kind::absorption;
    p.sigma_a = r.check_vec3(v, f, 0, 1000);
    return p;
}

// A hair colour: "skin" (the colour the skin shows under the root), "skin_melanin" (the
// skin's melanins), or [r, g, b] with each channel in (0, 1] (the colour a dense coat of
// such fibres shows, hair_pigments.h).
FurParams::Pigment colour(const JsonObjectFields &r, const json &v,
                          const std::string &f) {
    using Kind = FurParams::Pigment::Kind;
    FurParams::Pigment p;
    if (v.is_string() && v.get<std::string>() == "skin") return p;
    if (v.is_string() && v.get<std::string>() == "skin_melanin") {
        p.kind = Kind::skin_melanin;
        return p;
    }
    if (!v.is_array() || v.size() != 3)
        r.fail(f, "expected [r, g, b] (each in (0, 1]), \"skin\" or \"skin_melanin\"");
    p.kind = Kind::colour;
    p.colour = r.check_vec3(v, f, 0, 1);
    for (int k = 0; k < 3; ++k)
        if (!(p.colour[k] > 0))
            r.fail(f + "[" + std::to_string(k) + "]",
                   "must be in (0, 1]: a fibre of colour 0 would absorb everything");
    return p;
}

// One entry of colour_by_type: a colour as above, or {"melanin": [...]},
// {"cycles_melanin": [...]} or {"sigma_a": [...]}.
FurParams::Pigment type_pigment(const JsonObjectFields &r, const json &v,
                                const std::string &f) {
    if (!v.is_object()) return colour(r, v, f);
    JsonObjectFields e(v, f, r.file());
    const json *m = e.take("melanin");
    const json *c = e.take("cycles_melanin");
    const json *a = e.take("sigma_a");
    e.finish();
    if ((m != nullptr) + (c != nullptr) + (a != nullptr) != 1)
        r.fail(f,
               "expected {\"melanin\": [eumelanin, pheomelanin]}, "
               "{\"cycles_melanin\": [melanin, redness]} or {\"sigma_a\": [r, g, b]}");
    return m   ? melanin(r, *m, f + ".melanin")
           : c ? cycles_melanin(r, *c, f + ".cycles_melanin")
               : absorption(r, *a, f + ".sigma_a");
}

// "colour": {"default": colour, "in": {region: [r, g, b], ...}}: the coat's colour
// (any form `colour` takes) and, per region, the colour the hair turns to there.
FurParams::Pigment colour_by_region(const JsonObjectFields &r, const json &v,
                                    const std::string &f, FurParams *p) {
    if (p->regions.empty()) r.fail(f, "a colour by region needs the fur's \"regions\"");
    JsonObjectFields e(v, f, r.file());
    const json &def = e.require("default");
    const json &in = e.require("in");
    e.finish();
    const FurParams::Pigment base = colour(r, def, f + ".default");
    if (!in.is_object() || in.empty())
        r.fail(f + ".in", "expected an object {region: [r, g, b], ...}");
    for (const auto &[name, c] : in.items()) {
        const std::string fc = f + ".in." + name;
        const int region = p->regions.find_region(name);
        if (region < 0) r.fail(fc, "unknown region '" + name + "'");
        const FurParams::Pigment pc = colour(r, c, fc);
        if (pc.kind != FurParams::Pigment::Kind::colour)
            r.fail(fc, "expected [r, g, b] (each in (0, 1])");
        p->colour_in.push_back({region, pc.colour});
    }
    return base;
}

}  // namespace

FurParams read_fur(const json &j, const std::string &field,
                   const std::string &scene_path) {
    DeclaredFields r(j, field, scene_path);
    FurParams p;
    using F = FurParams;
    for (const auto &[key, bit] :
         {std::pair<const char *, uint32_t>{"density", F::given_density},
          {"length", F::given_length},
          {"root_radius", F::given_root_radius},
          {"tip_radius", F::given_tip_radius},
          {"clump_radius", F::given_clump_radius}})
        if (j.is_object() && j.contains(key)) p.given |= bit;
    // Regions first: the values below may name them.
    if (const json *v = r.take("regions")) {
        try {
            sim::parse_regions(*v, r.file(), &p.regions);
        } catch (const InputError &e) {
            throw e.under(r.path_prefix());
        }
    }
    using G = FurParams::Groomed;
    p.density = groomed(r, &p, G::density, "density", p.density, {0, 1e12});
    const std::vector<float> &dt = p.vary(G::density).by_type;
    if (!dt.empty() && *std::max_element(dt.begin(), dt.end()) <= 0)
        r.fail(r.field("density_by_type"), "every multiplier is 0: no strand could grow");
    p.seed = r.unsigned_integer("seed", p.seed, 0, ~0ull);
    p.max_strands = r.unsigned_integer("max_strands", p.max_strands, 1, 50'000'000);
    p.length = float(groomed(r, &p, G::length, "length", p.length, {0, 1e9, true}));
    p.length_variation = num(r, "length_variation", p.length_variation, 0, 0.99);
    p.root_radius = float(
        groomed(r, &p, G::root_radius, "root_radius", p.root_radius, {0, 1e9, true}));
    p.tip_radius =
        float(groomed(r, &p, G::tip_radius, "tip_radius", p.tip_radius, {0, 1e9, true}));
    p.segments = int(r.unsigned_integer("segments", uint64_t(p.segments), 1, 64));
    if (const json *v = r.take("comb")) {
        if (v->is_string() && v->get<std::string>() == "normal") {
            p.comb = FurParams::Comb::normal;
        } else if (v->is_string() && v->get<std::string>() == "field") {
            p.comb = FurParams::Comb::field;  // the pattern's own anisotropy field
            p.comb_pattern_field = true;
        } else if (v->is_object()) {
            // A field as a preset's simulation.anisotropy.field gives it.
            p.comb = FurParams::Comb::field;
            p.comb_field = sim::parse_field_spec(*v, r.field("comb"), r.file());
        } else if (v->is_array() && v->size() == 3) {
            for (int k = 0; k < 3; ++k)
                (k == 0   ? p.comb_direction.x
                 : k == 1 ? p.comb_direction.y
                          : p.comb_direction.z) =
                    float(r.check_number((*v)[k],
                                         r.field("comb") + "[" + std::to_string(k) + "]",
                                         -1e6, 1e6));
            const Vec3f c = p.comb_direction;
            if (c.x * c.x + c.y * c.y + c.z * c.z <= 0)
                r.fail(r.field("comb"), "must not be zero");
        } else {
            r.fail(r.field("comb"),
                   "expected [x, y, z] (a world direction), \"normal\", \"field\" (the "
                   "pattern's anisotropy field) or a field such as {\"along\": "
                   "\"body_axis\"}");
        }
    }
    if (r.has("comb_towards")) {
        p.comb_towards = r.vec3("comb_towards", p.comb_towards, -1e6, 1e6);
        if (dot(p.comb_towards, p.comb_towards) <= 0)
            r.fail(r.field("comb_towards"), "must not be zero");
    }
    p.comb_smoothing =
        int(r.unsigned_integer("comb_smoothing", uint64_t(p.comb_smoothing), 0, 1000));
    p.comb_angle_deg =
        float(groomed(r, &p, G::comb_angle, "comb_angle", p.comb_angle_deg, {0, 90}));
    p.comb_jitter_deg = num(r, "comb_jitter", p.comb_jitter_deg, 0, 60);
    p.gravity = num(r, "gravity", p.gravity, 0, 10);
    p.curl_radius =
        float(groomed(r, &p, G::curl_radius, "curl_radius", p.curl_radius, {0, 1}));
    p.curl_turns =
        float(groomed(r, &p, G::curl_turns, "curl_turns", p.curl_turns, {0, 100}));
    p.clump = float(groomed(r, &p, G::clump, "clump", p.clump, {0, 1}));
    p.clump_radius = num(r, "clump_radius", p.clump_radius, 0, 1e9, true);
    p.melanin_scale = num(r, "melanin_scale", p.melanin_scale, 0, 100);
    // One pigment for the coat: a colour, melanins, Cycles' melanin parameters, or the
    // absorption itself.
    std::string pigment_key;
    for (const char *key : {"colour", "melanin", "cycles_melanin", "sigma_a"})
        if (const json *v = r.take(key)) {
            if (!pigment_key.empty())
                r.fail(r.field(key), "give one of \"" + r.spelled("colour") +
                                         "\", \"melanin\", \"cycles_melanin\" and "
                                         "\"sigma_a\" (\"" +
                                         pigment_key + "\" is given too)");
            pigment_key = r.spelled(key);
            const std::string f = r.field(key);
            const std::string k = key;
            if (k == "colour" && sim::is_local_value(*v)) {
                p.pigment = colour_by_region(r, *v, f, &p);
                continue;
            }
            p.pigment = k == "colour"    ? colour(r, *v, f)
                        : k == "melanin" ? melanin(r, *v, f)
                        : k == "sigma_a" ? absorption(r, *v, f)
                                         : cycles_melanin(r, *v, f);
        }
    if (const json *v = r.take("colour_by_type")) {
        const std::string f = r.field("colour_by_type");
        if (!v->is_array() || v->empty() || v->size() > 16)
            r.fail(f, "expected an array of 1 to 16 hair colours (one per cell type)");
        for (size_t i = 0; i < v->size(); ++i)
            p.pigment_by_type.push_back(
                type_pigment(r, (*v)[i], f + "[" + std::to_string(i) + "]"));
    }
    p.melanin_jitter = num(r, "melanin_jitter", p.melanin_jitter, 0, 1);
    p.beta_m = float(groomed(r, &p, G::beta_m, "beta_m", p.beta_m, {0, 1, true}));
    p.beta_n = float(groomed(r, &p, G::beta_n, "beta_n", p.beta_n, {0, 1, true}));
    p.alpha_deg = num(r, "alpha", p.alpha_deg, -44, 44);
    p.min_pixel_width = num(r, "min_pixel_width", p.min_pixel_width, 0, 16);
    if (const json *v = r.take("curve")) {
        const std::string s = v->is_string() ? v->get<std::string>() : "";
        if (s == "round")
            p.curve = FurParams::Curve::round;
        else if (s == "flat")
            p.curve = FurParams::Curve::flat;
        else
            r.fail(r.field("curve"),
                   "expected \"round\" (B-spline tubes, close-ups) or "
                   "\"flat\" (linear ribbons, distance)");
    }
    if (p.curve == FurParams::Curve::round && p.segments < 2)
        r.fail(r.field("segments"),
               "a round (B-spline) strand needs at least 2 segments");
    r.finish();
    return p;
}

}  // namespace pelage::renderer
