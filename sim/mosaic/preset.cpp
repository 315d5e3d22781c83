#include "sim/mosaic/preset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "sim/control/control_parse.h"
#include "sim/core/colour_spelling.h"
#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"
#include "sim/core/spelling.h"

namespace pelage::sim {

using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// The preset's fields (sim/core/json_fields.h) and its square matrices of numbers in a
// range.
class Reader : public JsonFields {
  public:
    using JsonFields::JsonFields;

    std::vector<std::vector<double>> matrix(const json &v, const std::string &path,
                                            size_t n, double lo, double hi) const {
        if (!v.is_array() || v.size() != n)
            fail(path,
                 "expected a " + std::to_string(n) + "x" + std::to_string(n) + " matrix");
        std::vector<std::vector<double>> m;
        for (size_t i = 0; i < n; ++i) {
            const std::string row = path + "[" + std::to_string(i) + "]";
            m.push_back(numbers(v[i], row, n));
            for (size_t j = 0; j < n; ++j)
                if (m[i][j] < lo || m[i][j] > hi)
                    fail(row + "[" + std::to_string(j) + "]",
                         format(m[i][j]) + ": must be in [" + format(lo) + ", " +
                             format(hi) + "]");
        }
        return m;
    }
};

constexpr double probability_tolerance = 1e-6;  // rows and initial probabilities sum to 1

// A type's division_time and initial_probability may vary by region (`ot` is the same
// node read in its listed order); their defaults go into the CellType.
CellType parse_type(const Reader &r, const json &t, const std::string &path,
                    const ordered_json &ot, const ControlSpec &control,
                    LocalValue *division_time, LocalValue *initial_probability) {
    r.check_keys(t, path,
                 {"name", "colour", "color", "eumelanin", "pheomelanin", "division_time",
                  "initial_probability", "notes"});
    CellType c;
    c.name = r.string(t, path, "name", "", true);
    if (c.name.empty() || c.name.size() > 64)
        r.fail(path + ".name", "must have 1 to 64 characters");
    // "colour", or "color" (sim/core/colour_spelling.h), named as the preset spells it.
    const std::string key = spelling_in(t, "colour", r.file(), path + ".colour");
    const std::string colour = path + "." + key;
    if (!t.contains(key)) r.fail(colour, "missing");
    const auto rgb = r.numbers(t[key], colour, 3);
    for (int k = 0; k < 3; ++k) {
        if (rgb[k] < 0) r.fail(colour, "components must be >= 0 (linear RGB)");
        c.colour[k] = static_cast<float>(rgb[k]);
    }
    c.eumelanin = static_cast<float>(r.number(t, path, "eumelanin", 0));
    c.pheomelanin = static_cast<float>(r.number(t, path, "pheomelanin", 0));
    if (c.eumelanin < 0 || c.pheomelanin < 0)
        r.fail(path, "melanin concentrations must be >= 0");
    if (!t.contains("division_time"))
        r.fail(path + ".division_time", "missing (a number or \"never\")");
    const json &dt = t["division_time"];
    if (is_local_value(ot["division_time"])) {
        *division_time =
            parse_local_value(ot["division_time"], path + ".division_time", r.file(),
                              control, {0, std::numeric_limits<double>::max(), true});
        c.division_time = division_time->value;
    } else if (dt.is_string()) {
        if (dt.get<std::string>() != "never")
            r.fail(path + ".division_time", "expected a number > 0 or \"never\"");
    } else {
        c.division_time = r.number(t, path, "division_time", 0);
        if (c.division_time <= 0)
            r.fail(path + ".division_time",
                   Reader::format(c.division_time) + ": must be > 0 (or \"never\")");
    }
    if (t.contains("initial_probability") && is_local_value(ot["initial_probability"])) {
        *initial_probability =
            parse_local_value(ot["initial_probability"], path + ".initial_probability",
                              r.file(), control, {0, 1});
        c.initial_probability = initial_probability->value;
        return c;
    }
    c.initial_probability = r.number(t, path, "initial_probability", 0, true);
    if (c.initial_probability < 0 || c.initial_probability > 1)
        r.fail(path + ".initial_probability",
               Reader::format(c.initial_probability) + ": must be in [0, 1]");
    return c;
}

SimParams parse_plain_sim(const Reader &r, const json &s, const ControlSpec &control);

// w_r, w_d, w_a, anisotropy.magnitude and initial_weight may vary by region (`os` is
// the same node read in its listed order); their defaults go into SimParams.
SimParams parse_sim(const Reader &r, const json &s, const ordered_json &os,
                    ControlSpec *control) {
    const std::string p = "simulation";
    r.check_keys(
        s, p,
        {"initial_cells", "initial_density", "initial_spacing", "initial_relax_steps",
         "initial_relax_alpha", "initial_relax_tolerance", "w_r", "w_d", "w_a",
         "anisotropy", "relax", "local_steps", "rho", "end_time", "target_cells",
         "division_distribution", "child_radius_factor", "initial_weight", "notes"});
    // A local value replaces the plain number the checks below read.
    json plain = s;
    auto local = [&](const ordered_json &node, json *plain_node, const std::string &path,
                     const std::string &key, ValueRange range, LocalValue *out) {
        if (!node.contains(key) || !is_local_value(node[key])) return;
        *out = parse_local_value(node[key], path + "." + key, r.file(), *control, range);
        (*plain_node)[key] = out->value;
    };
    const double inf = std::numeric_limits<double>::max();
    local(os, &plain, p, "w_r", {0, inf, true}, &control->w_r);
    local(os, &plain, p, "w_d", {0, inf, true}, &control->w_d);
    local(os, &plain, p, "w_a", {0, 1}, &control->w_a);
    local(os, &plain, p, "initial_weight", {0, inf}, &control->initial_weight);
    if (os.contains("anisotropy") && os["anisotropy"].is_object())
        local(os["anisotropy"], &plain["anisotropy"], p + ".anisotropy", "magnitude",
              {0, inf}, &control->anisotropy_magnitude);
    if (control->initial_weight.value <= 0 && !control->initial_weight.local())
        r.fail(p + ".initial_weight", "must be > 0 (a relative density)");
    const SimParams o = parse_plain_sim(r, plain, *control);
    // The control holds every one of them, local or constant.
    control->w_r.value = o.w_r;
    control->w_d.value = o.w_d;
    control->w_a.value = o.w_a;
    control->anisotropy_magnitude.value = o.anisotropy_magnitude;
    return o;
}

SimParams parse_plain_sim(const Reader &r, const json &s, const ControlSpec &control) {
    const std::string p = "simulation";
    SimParams o;
    auto positive = [&](const std::string &key, double v) {
        if (!(v > 0)) r.fail(p + "." + key, Reader::format(v) + ": must be > 0");
        return v;
    };
    auto non_negative = [&](const std::string &key, double v) {
        if (v < 0) r.fail(p + "." + key, Reader::format(v) + ": must be >= 0");
        return v;
    };
    auto integer = [&](const std::string &key, double v, double hi) {
        if (v != std::floor(v) || v < 0 || v > hi)
            r.fail(p + "." + key, Reader::format(v) + ": must be an integer in [0, " +
                                      Reader::format(hi) + "]");
        return v;
    };
    o.initial_cells = static_cast<uint64_t>(
        integer("initial_cells", r.number(s, p, "initial_cells", 0), 1e9));
    o.initial_density =
        non_negative("initial_density", r.number(s, p, "initial_density", 0));
    o.initial_spacing =
        non_negative("initial_spacing", r.number(s, p, "initial_spacing", 0));
    if (o.initial_spacing > 1)
        r.fail(p + ".initial_spacing",
               Reader::format(o.initial_spacing) +
                   ": a fraction of the body length, expected at most 1");
    const int given =
        (o.initial_cells > 0) + (o.initial_density > 0) + (o.initial_spacing > 0);
    if (given == 0) r.fail(p, "needs initial_cells, initial_density or initial_spacing");
    if (given > 1)
        r.fail(p,
               "initial_cells, initial_density and initial_spacing conflict: give one");
    o.initial_relax_steps = static_cast<int>(integer(
        "initial_relax_steps", r.number(s, p, "initial_relax_steps", 50), 100000));
    o.initial_relax_alpha = r.number(s, p, "initial_relax_alpha", 0);
    if (o.initial_relax_alpha < 0 || o.initial_relax_alpha >= 1)
        r.fail(p + ".initial_relax_alpha", "must be in [0, 1)");
    o.initial_relax_tolerance = non_negative(
        "initial_relax_tolerance", r.number(s, p, "initial_relax_tolerance", 0.01));
    o.w_r = positive("w_r", r.number(s, p, "w_r", 0, true));
    o.w_d = positive("w_d", r.number(s, p, "w_d", 0, true));
    o.w_a = r.number(s, p, "w_a", 0);
    if (o.w_a < 0 || o.w_a > 1)
        r.fail(p + ".w_a", Reader::format(o.w_a) + ": must be in [0, 1]");
    if (s.contains("anisotropy")) {
        const json &a = s["anisotropy"];
        r.check_keys(a, p + ".anisotropy", {"direction", "field", "magnitude"});
        if (a.contains("field")) {
            if (a.contains("direction"))
                r.fail(p + ".anisotropy",
                       "\"direction\" and \"field\" conflict: give one");
            o.anisotropy_field =
                parse_field_spec(a["field"], p + ".anisotropy.field", r.file());
        } else {
            if (!a.contains("direction"))
                r.fail(p + ".anisotropy.direction", "missing (or give a \"field\")");
            const auto d = r.numbers(a["direction"], p + ".anisotropy.direction", 3);
            const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (len == 0)
                r.fail(p + ".anisotropy.direction", "must not be the zero vector");
            o.anisotropy_direction = {d[0] / len, d[1] / len, d[2] / len};
        }
        o.anisotropy_magnitude = non_negative(
            "anisotropy.magnitude", r.number(a, p + ".anisotropy", "magnitude", 1));
    }
    double w_a_max = o.w_a;
    for (const auto &[region, v] : control.w_a.in) w_a_max = std::max(w_a_max, v);
    if (w_a_max > 0 && o.anisotropy_magnitude == 0 &&
        !control.anisotropy_magnitude.local())
        r.fail(p + ".w_a", "w_a > 0 needs an anisotropy {direction or field, magnitude}");
    const std::string relax = r.string(s, p, "relax", "local");
    if (relax == "local")
        o.relax = RelaxMode::local;
    else if (relax == "global")
        o.relax = RelaxMode::global;
    else
        r.fail(p + ".relax", "'" + relax + "': expected \"local\" or \"global\"");
    o.local_steps = static_cast<int>(
        integer("local_steps", r.number(s, p, "local_steps", 4), 100000));
    if (o.local_steps < 1) r.fail(p + ".local_steps", "must be >= 1");
    o.rho = positive("rho", r.number(s, p, "rho", 0, true));
    o.end_time = non_negative("end_time", r.number(s, p, "end_time", 0, true));
    o.target_cells = static_cast<uint64_t>(
        integer("target_cells", r.number(s, p, "target_cells", 0), 1e9));
    if (o.target_cells > 0 && o.initial_cells == 0)
        r.fail(p + ".target_cells",
               "needs initial_cells: it is the count initial_cells grows to, and scales "
               "with the initial count of each run");
    if (o.end_time * o.rho > 1e7)
        r.fail(p, "end_time · rho exceeds 10^7 relaxation steps");
    const std::string dist = r.string(s, p, "division_distribution", "poisson");
    if (dist == "poisson")
        o.division_distribution = DivisionDistribution::poisson;
    else if (dist == "exponential")
        o.division_distribution = DivisionDistribution::exponential;
    else
        r.fail(p + ".division_distribution",
               "'" + dist + "': expected \"poisson\" or \"exponential\"");
    o.child_radius_factor =
        positive("child_radius_factor", r.number(s, p, "child_radius_factor", 0.005));
    if (o.child_radius_factor > 1) r.fail(p + ".child_radius_factor", "must be <= 1");
    return o;
}

json parse_json(const std::string &text, const std::string &file) {
    try {
        return json::parse(text);
    } catch (const json::exception &e) {
        // parse_error, and out_of_range for a number such as 1e400 that overflows a
        // double.
        throw InputError(file, 0, "", std::string("not valid JSON: ") + e.what());
    }
}

// The keys a preset that extends another may give: its own words and colours; the
// cells' dynamics, regions and masks are the base's.
const std::set<std::string> extends_keys = {"name",        "extends",  "animal",
                                            "description", "source",   "notes",
                                            "colours",     "melanins", "colors"};

// A type name of the base, or an InputError at `path` naming the closest one.
void check_type_name(const Reader &r, const ordered_json &base_types,
                     const std::string &name, const std::string &path,
                     const std::string &base) {
    std::vector<std::string> names;
    for (const auto &t : base_types)
        if (t.is_object() && t.contains("name") && t["name"].is_string())
            names.push_back(t["name"].get<std::string>());
    if (std::find(names.begin(), names.end(), name) != names.end()) return;
    const std::string guess = closest_name(name, names);
    std::string list;
    for (const auto &n : names) list += (list.empty() ? "" : ", ") + n;
    r.fail(path, "'" + name + "' is not a type of '" + base + "'" +
                     (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                     "; its types: " + list);
}

// `child` extends the preset `child.extends` of the same folder: the base's document
// with the child's name, words, colours and melanins, without the base's "published"
// figures (they describe the base's runs and are checked there) and without "extends".
// The base may not itself extend another preset. It is looked for beside the child,
// then in `presets_dir` (the shipped presets), so a user's file can extend a shipped
// preset from any folder.
std::string extended_text(const Reader &r, const ordered_json &child,
                          const std::string &presets_dir) {
    r.check_keys(child, "", extends_keys);
    if (!child.contains("name")) r.fail("name", "missing");
    const ordered_json &e = child["extends"];
    if (!e.is_string()) r.fail("extends", "expected the name of a preset");
    const std::string base = e.get<std::string>();
    if (base.empty() || base.find('/') != std::string::npos ||
        base.find('\\') != std::string::npos || base.ends_with(".json"))
        r.fail("extends",
               "'" + base + "': expected the name of a preset (no path, no .json)");
    std::filesystem::path path =
        std::filesystem::path(r.file()).parent_path() / (base + ".json");
    if (!std::filesystem::exists(path) && !presets_dir.empty() &&
        std::filesystem::exists(std::filesystem::path(presets_dir) / (base + ".json")))
        path = std::filesystem::path(presets_dir) / (base + ".json");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        r.fail("extends",
               "'" + base + "': no preset " + path.string() +
                   (presets_dir.empty() ? std::string() : " nor in " + presets_dir));
    std::ostringstream ss;
    ss << in.rdbuf();
    ordered_json doc;
    try {
        doc = ordered_json::parse(ss.str());
    } catch (const json::exception &x) {
        throw InputError(path.string(), 0, "",
                         std::string("not valid JSON: ") + x.what());
    }
    // A base that extends another is named as such before its own (absent) types.
    if (doc.is_object() && doc.contains("extends"))
        r.fail("extends",
               "'" + base + "' itself extends '" +
                   (doc["extends"].is_string() ? doc["extends"].get<std::string>()
                                               : std::string("?")) +
                   "': extend a preset that gives its own types");
    if (!doc.is_object() || !doc.contains("types") || !doc["types"].is_array())
        throw InputError(path.string(), 0, "types", "missing");
    for (const char *key : {"name", "animal", "description", "source", "notes"})
        if (child.contains(key)) {
            if (!child[key].is_string()) r.fail(key, "expected a string");
            doc[key] = child[key];
        }
    doc.erase("published");
    const std::string ckey = spelling_in(child, "colours", r.file(), "colours");
    if (!child.contains(ckey) && !child.contains("melanins"))
        r.fail("colours",
               "missing: a preset that extends another gives its own colours "
               "{\"TYPE\": [r, g, b], ...}");
    auto type_at = [&](const std::string &name) -> ordered_json & {
        for (auto &t : doc["types"])
            if (t.is_object() && t.contains("name") && t["name"] == name) return t;
        return doc["types"][0];  // not reached: check_type_name throws first
    };
    if (child.contains(ckey)) {
        const ordered_json &c = child[ckey];
        if (!c.is_object() || c.empty())
            r.fail(ckey, "expected an object {\"TYPE\": [r, g, b], ...}");
        for (const auto &[name, rgb] : c.items()) {
            const std::string at = ckey + "." + name;
            check_type_name(r, doc["types"], name, at, base);
            const auto v = r.numbers(rgb, at, 3);
            for (double x : v)
                if (x < 0) r.fail(at, "components must be >= 0 (linear RGB)");
            ordered_json &t = type_at(name);
            t.erase("color");
            t["colour"] = rgb;
        }
    }
    if (child.contains("melanins")) {
        const ordered_json &m = child["melanins"];
        if (!m.is_object() || m.empty())
            r.fail(
                "melanins",
                "expected an object {\"TYPE\": {\"eumelanin\": e, \"pheomelanin\": p}}");
        for (const auto &[name, v] : m.items()) {
            const std::string at = "melanins." + name;
            check_type_name(r, doc["types"], name, at, base);
            r.check_keys(v, at, {"eumelanin", "pheomelanin"});
            ordered_json &t = type_at(name);
            for (const char *k : {"eumelanin", "pheomelanin"})
                if (v.contains(k)) {
                    if (r.number(v[k], at + "." + k) < 0)
                        r.fail(at + "." + k, "must be >= 0");
                    t[k] = v[k];
                }
        }
    }
    return doc.dump();
}

}  // namespace

Preset parse_preset(const std::string &text, const std::string &file,
                    const std::string &presets_dir) {
    const Reader r(file);
    json j = parse_json(text, file);
    if (j.is_object() && j.contains("extends")) {
        const std::string base =
            j["extends"].is_string() ? j["extends"].get<std::string>() : "";
        // The merged document is checked as any preset, its errors named in this file.
        Preset p =
            parse_preset(extended_text(r, ordered_json::parse(text), presets_dir), file);
        p.extends = base;
        return p;
    }
    r.check_keys(j, "",
                 {"name", "description", "source", "types", "mutation", "adhesion",
                  "repulsiveness", "simulation", "published", "regions", "masks", "notes",
                  "growth", "animal"});
    // The same document with objects in their listed order, for the control blocks.
    const ordered_json oj = ordered_json::parse(text);
    Preset preset;
    if (oj.contains("regions")) parse_regions(oj["regions"], file, &preset.control);
    preset.name = r.string(j, "", "name", "", true);
    preset.description = r.string(j, "", "description", "");
    preset.animal = r.string(j, "", "animal", "");

    // --- Types ---
    if (!j.contains("types")) r.fail("types", "missing");
    const json &jt = j["types"];
    if (!jt.is_array() || jt.size() < 1 || jt.size() > max_cell_types)
        r.fail("types", "expected an array of 1 to " + std::to_string(max_cell_types) +
                            " cell types");
    std::vector<CellType> types;
    std::set<std::string> names;
    std::vector<std::string> type_names;
    double sum = 0;
    preset.control.division_time.resize(jt.size());
    preset.control.initial_probability.resize(jt.size());
    for (size_t i = 0; i < jt.size(); ++i) {
        const std::string path = "types[" + std::to_string(i) + "]";
        types.push_back(parse_type(r, jt[i], path, oj["types"][i], preset.control,
                                   &preset.control.division_time[i],
                                   &preset.control.initial_probability[i]));
        type_names.push_back(types.back().name);
        if (!names.insert(types.back().name).second)
            r.fail(path + ".name", "'" + types.back().name + "' is used twice");
        sum += types.back().initial_probability;
    }
    if (std::abs(sum - 1) > probability_tolerance)
        r.fail("types[*].initial_probability",
               "sum to " + Reader::format(sum) + ", expected 1");
    const size_t n = types.size();

    // --- Mutation (row = parent), identity by default ---
    std::vector<std::vector<double>> mutation(n, std::vector<double>(n, 0));
    for (size_t i = 0; i < n; ++i) mutation[i][i] = 1;
    if (j.contains("mutation")) {
        mutation = r.matrix(j["mutation"], "mutation", n, 0, 1);
        for (size_t i = 0; i < n; ++i) {
            double row = 0;
            for (double v : mutation[i]) row += v;
            if (std::abs(row - 1) > probability_tolerance)
                r.fail("mutation[" + std::to_string(i) + "]",
                       "sums to " + Reader::format(row) + ", expected 1");
        }
    }

    // --- Adhesion α, or Teo's repulsiveness 1 − α (exactly one) ---
    const bool has_a = j.contains("adhesion"), has_r = j.contains("repulsiveness");
    if (has_a == has_r)
        r.fail("adhesion", has_a ? "adhesion and repulsiveness conflict: give one"
                                 : "missing (or give repulsiveness = 1 - adhesion)");
    // Adhesion may vary by region: {"default": matrix, "in": {region: matrix, ...}}.
    const bool local_adhesion = has_a && j["adhesion"].is_object();
    if (local_adhesion) {
        r.check_keys(j["adhesion"], "adhesion", {"default", "in"});
        if (!j["adhesion"].contains("default")) r.fail("adhesion.default", "missing");
        const ordered_json &in = oj["adhesion"]["in"];
        if (!in.is_object() || in.empty())
            r.fail("adhesion.in", "expected an object {region: matrix, ...}");
        for (const auto &[name, m] : in.items()) {
            const int region = preset.control.find_region(name);
            if (region < 0)
                r.fail("adhesion.in." + name, "unknown region '" + name + "'");
            preset.control.adhesion_in.push_back(
                {region, r.matrix(json(m), "adhesion.in." + name, n, 0, 1)});
        }
    }
    std::vector<std::vector<double>> alpha =
        has_a ? r.matrix(local_adhesion ? j["adhesion"]["default"] : j["adhesion"],
                         local_adhesion ? "adhesion.default" : "adhesion", n, 0, 1)
              : r.matrix(j["repulsiveness"], "repulsiveness", n, 0, 1);
    if (has_r)
        for (auto &row : alpha)
            for (double &v : row) v = 1 - v;

    if (j.contains("masks")) parse_masks(oj["masks"], file, type_names, &preset.control);

    if (!j.contains("simulation")) r.fail("simulation", "missing");
    preset.params = parse_sim(r, j["simulation"], oj["simulation"], &preset.control);
    if (j.contains("published") && !j["published"].is_object())
        r.fail("published", "expected an object");
    if (j.contains("growth"))
        preset.growth = parse_growth(j["growth"], "growth", file,
                                     std::filesystem::path(file).parent_path().string());
    preset.types = CellTypes(std::move(types), std::move(mutation), std::move(alpha));
    preset.json_text = j.dump();
    return preset;
}

Preset load_preset_file(const std::string &path, const std::string &presets_dir) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open preset file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parse_preset(ss.str(), path, presets_dir);
}

std::vector<std::string> preset_names(const std::string &presets_dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto &e : std::filesystem::directory_iterator(presets_dir, ec))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

Preset load_preset(const std::string &name_or_path, const std::string &presets_dir,
                   const std::string &file, const std::string &field) {
    const bool is_path = name_or_path.find('/') != std::string::npos ||
                         (name_or_path.size() > 5 && name_or_path.ends_with(".json"));
    if (is_path) return load_preset_file(name_or_path, presets_dir);
    const std::filesystem::path path =
        std::filesystem::path(presets_dir) / (name_or_path + ".json");
    if (!std::filesystem::exists(path)) {
        const std::vector<std::string> names = preset_names(presets_dir);
        std::string list;
        for (const auto &n : names) list += (list.empty() ? "" : ", ") + n;
        const std::string guess = closest_name(name_or_path, names);
        throw InputError(
            file, 0, field,
            "unknown preset '" + name_or_path + "'" +
                (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                "; available: " + (list.empty() ? "none found in " + presets_dir : list) +
                " (`pelage presets` describes them)");
    }
    return load_preset_file(path.string(), presets_dir);
}

}  // namespace pelage::sim
