#include "renderer/scene_file/scene_fur.h"

#include <algorithm>
#include <cmath>

#include "sim/core/json_fields.h"

namespace pelage::renderer {

namespace {

using json = nlohmann::json;
using sim::JsonObjectFields;

// A list of per-cell-type multipliers, each in (0, 1000] (or [0, 1000] when zero_ok).
std::vector<float> per_type(JsonObjectFields &r, const std::string &key, bool zero_ok) {
    const json *v = r.take(key);
    if (!v) return {};
    if (!v->is_array() || v->empty() || v->size() > 16)
        r.fail(r.field(key), "expected an array of 1 to 16 numbers (one per cell type)");
    std::vector<float> out;
    for (size_t i = 0; i < v->size(); ++i)
        out.push_back(float(r.check_number(
            (*v)[i], r.field(key) + "[" + std::to_string(i) + "]", 0, 1000, !zero_ok)));
    return out;
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
    e.finish();
    if ((m != nullptr) == (c != nullptr))
        r.fail(f,
               "expected {\"melanin\": [eumelanin, pheomelanin]} or "
               "{\"cycles_melanin\": [melanin, redness]}");
    return m ? melanin(r, *m, f + ".melanin")
             : cycles_melanin(r, *c, f + ".cycles_melanin");
}

}  // namespace

FurParams read_fur(const json &j, const std::string &field,
                   const std::string &scene_path) {
    JsonObjectFields r(j, field, scene_path);
    FurParams p;
    using F = FurParams;
    for (const auto &[key, bit] :
         {std::pair<const char *, uint32_t>{"density", F::given_density},
          {"length", F::given_length},
          {"root_radius", F::given_root_radius},
          {"tip_radius", F::given_tip_radius},
          {"clump_radius", F::given_clump_radius}})
        if (j.is_object() && j.contains(key)) p.given |= bit;
    if (const json *v = r.take("density"))
        p.density = r.check_number(*v, r.field("density"), 0, 1e12);
    p.density_by_type = per_type(r, "density_by_type", true);
    if (!p.density_by_type.empty() &&
        *std::max_element(p.density_by_type.begin(), p.density_by_type.end()) <= 0)
        r.fail(r.field("density_by_type"), "every multiplier is 0: no strand could grow");
    p.seed = r.unsigned_integer("seed", p.seed, 0, ~0ull);
    p.max_strands = r.unsigned_integer("max_strands", p.max_strands, 1, 50'000'000);
    p.length = num(r, "length", p.length, 0, 1e9, true);
    p.length_by_type = per_type(r, "length_by_type", false);
    p.length_variation = num(r, "length_variation", p.length_variation, 0, 0.99);
    p.root_radius = num(r, "root_radius", p.root_radius, 0, 1e9, true);
    p.tip_radius = num(r, "tip_radius", p.tip_radius, 0, 1e9, true);
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
    p.comb_angle_deg = num(r, "comb_angle", p.comb_angle_deg, 0, 90);
    p.comb_jitter_deg = num(r, "comb_jitter", p.comb_jitter_deg, 0, 60);
    p.gravity = num(r, "gravity", p.gravity, 0, 10);
    p.curl_radius = num(r, "curl_radius", p.curl_radius, 0, 1);
    p.curl_turns = num(r, "curl_turns", p.curl_turns, 0, 100);
    p.clump = num(r, "clump", p.clump, 0, 1);
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
    p.beta_m = num(r, "beta_m", p.beta_m, 0, 1, true);
    p.beta_n = num(r, "beta_n", p.beta_n, 0, 1, true);
    p.alpha_deg = num(r, "alpha", p.alpha_deg, -44, 44);
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
