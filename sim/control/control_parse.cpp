#include "sim/control/control_parse.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>

#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"

namespace pelage::sim {

using nlohmann::ordered_json;

bool ControlSpec::any_local() const {
    if (w_r.local() || w_d.local() || w_a.local() || anisotropy_magnitude.local() ||
        initial_weight.local() || !adhesion_in.empty())
        return true;
    for (const LocalValue &v : division_time)
        if (v.local()) return true;
    for (const LocalValue &v : initial_probability)
        if (v.local()) return true;
    return false;
}

bool ControlSpec::needs_mesh_data() const {
    for (const RegionSpec &r : regions)
        if (r.kind == RegionSpec::Kind::attribute || r.kind == RegionSpec::Kind::texture)
            return true;
    return false;
}

int ControlSpec::find_region(const std::string &name) const {
    for (size_t i = 0; i < region_names.size(); ++i)
        if (region_names[i] == name) return static_cast<int>(i);
    return -1;
}

namespace {

// The fields of the block at `path` (sim/core/json_fields.h); a key names a field
// relative to it, "" the block itself.
class Fields {
  public:
    Fields(const std::string &file, std::string path)
        : m_fields(file), m_path(std::move(path)) {}
    [[noreturn]] void fail(const std::string &key, const std::string &message) const {
        m_fields.fail(at(key), message);
    }
    void keys(const ordered_json &obj, const std::set<std::string> &allowed) const {
        m_fields.check_keys(obj, m_path, allowed);
    }
    double number(const ordered_json &obj, const std::string &key, double fallback,
                  bool required = false) const {
        return m_fields.number(obj, m_path, key, fallback, required);
    }
    double non_negative(const ordered_json &obj, const std::string &key,
                        double fallback) const {
        const double v = number(obj, key, fallback);
        if (v < 0) fail(key, JsonFields::format(v) + ": must be >= 0");
        return v;
    }
    std::string string(const ordered_json &obj, const std::string &key) const {
        return m_fields.non_empty_string(*m_fields.find(obj, m_path, key, true), at(key));
    }
    std::array<double, 3> point(const ordered_json &v, const std::string &key) const {
        const std::vector<double> p =
            m_fields.numbers(v, at(key), 3, "expected finite numbers");
        return {p[0], p[1], p[2]};
    }
    const std::string &path() const { return m_path; }

  private:
    std::string at(const std::string &key) const {
        return key.empty() ? m_path : m_path + "." + key;
    }

    JsonFields m_fields;
    std::string m_path;
};

// Operand names of any/all/not, resolved once every name is known.
int operand(const Fields &f, const std::string &key, const ordered_json &v,
            const ControlSpec &spec) {
    if (!v.is_string()) f.fail(key, "expected a region name");
    const int i = spec.find_region(v.get<std::string>());
    if (i < 0) f.fail(key, "unknown region '" + v.get<std::string>() + "'");
    return i;
}

RegionSpec parse_region(const ordered_json &j, const Fields &f, const std::string &file,
                        const ControlSpec &spec) {
    static const std::set<std::string> kinds = {"height", "near", "attribute", "texture",
                                                "any",    "all",  "not",       "notes"};
    f.keys(j, kinds);
    int given = 0;
    for (const auto &[key, value] : j.items()) given += key != "notes";
    if (given != 1)
        f.fail("",
               "expected exactly one of height, near, attribute, texture, any, all, "
               "not");
    RegionSpec r;
    if (j.contains("height")) {
        r.kind = RegionSpec::Kind::height;
        const Fields h(file, f.path() + ".height");
        const ordered_json &o = j["height"];
        h.keys(o, {"axis", "below", "above", "blend"});
        if (o.contains("axis")) {
            r.axis = h.point(o["axis"], "axis");
            const double len = std::sqrt(r.axis[0] * r.axis[0] + r.axis[1] * r.axis[1] +
                                         r.axis[2] * r.axis[2]);
            if (len == 0) h.fail("axis", "must not be the zero vector");
            for (double &a : r.axis) a /= len;
        }
        r.has_below = o.contains("below");
        r.has_above = o.contains("above");
        if (!r.has_below && !r.has_above) h.fail("", "needs below, above or both");
        r.below = h.number(o, "below", 1);
        r.above = h.number(o, "above", 0);
        r.blend = h.non_negative(o, "blend", 0);
    } else if (j.contains("near")) {
        r.kind = RegionSpec::Kind::near;
        const Fields n(file, f.path() + ".near");
        const ordered_json &o = j["near"];
        n.keys(o, {"points", "space", "within", "blend"});
        if (!o.contains("points")) n.fail("points", "missing");
        const ordered_json &pts = o["points"];
        if (!pts.is_array() || pts.empty() || pts.size() > 1000)
            n.fail("points", "expected an array of 1 to 64 points [x, y, z]");
        for (size_t i = 0; i < pts.size(); ++i)
            r.points.push_back(n.point(pts[i], "points[" + std::to_string(i) + "]"));
        const auto space = o.find("space");
        if (space != o.end()) {
            if (*space == "box")
                r.box_space = true;
            else if (*space == "world")
                r.box_space = false;
            else
                n.fail("space", "expected \"box\" or \"world\"");
        }
        r.within = n.non_negative(o, "within", 0);
        r.blend = n.non_negative(o, "blend", 0);
        if (!o.contains("within")) n.fail("within", "missing");
        if (r.within > 1 || r.blend > 1)
            n.fail("", "within and blend are fractions of the body length, at most 1");
    } else if (j.contains("attribute")) {
        r.kind = RegionSpec::Kind::attribute;
        r.attribute = f.string(j, "attribute");
    } else if (j.contains("texture")) {
        r.kind = RegionSpec::Kind::texture;
        r.texture = f.string(j, "texture");
        const std::filesystem::path p(r.texture);
        if (p.is_relative())
            r.texture = (std::filesystem::path(file).parent_path() / p).string();
    } else if (j.contains("any") || j.contains("all")) {
        const std::string key = j.contains("any") ? "any" : "all";
        r.kind = key == "any" ? RegionSpec::Kind::any : RegionSpec::Kind::all;
        const ordered_json &list = j[key];
        if (!list.is_array() || list.empty())
            f.fail(key, "expected a non-empty array of region names");
        for (size_t i = 0; i < list.size(); ++i)
            r.operands.push_back(
                operand(f, key + "[" + std::to_string(i) + "]", list[i], spec));
    } else {
        r.kind = RegionSpec::Kind::negate;
        r.operands.push_back(operand(f, "not", j["not"], spec));
    }
    return r;
}

}  // namespace

void parse_regions(const ordered_json &regions, const std::string &file,
                   ControlSpec *spec) {
    const Fields top(file, "regions");
    if (!regions.is_object()) top.fail("", "expected an object of named regions");
    if (regions.size() > 64) top.fail("", "at most 64 regions");
    for (const auto &[name, value] : regions.items()) {
        if (name.empty() || name.size() > 64)
            top.fail(name, "a region name has 1 to 64 characters");
        spec->region_names.push_back(name);
    }
    for (const auto &[name, value] : regions.items()) {
        const Fields f(file, "regions." + name);
        // A texture region's channel sits beside its path.
        if (value.is_object() && value.contains("texture") && value.contains("channel")) {
            ordered_json copy = value;
            const ordered_json channel = copy["channel"];
            copy.erase("channel");
            RegionSpec r = parse_region(copy, f, file, *spec);
            if (!channel.is_number_integer() || channel.get<int64_t>() < 0 ||
                channel.get<int64_t>() > 3)
                f.fail("channel", "expected an integer in [0, 3]");
            r.channel = static_cast<int>(channel.get<int64_t>());
            spec->regions.push_back(std::move(r));
        } else {
            spec->regions.push_back(parse_region(value, f, file, *spec));
        }
    }
    // No region may depend on itself through any/all/not.
    const size_t n = spec->regions.size();
    std::vector<int> state(n, 0);  // 0 unseen, 1 on the stack, 2 done
    std::function<void(size_t)> visit = [&](size_t i) {
        if (state[i] == 2) return;
        if (state[i] == 1)
            top.fail(spec->region_names[i], "refers to itself through any/all/not");
        state[i] = 1;
        for (int o : spec->regions[i].operands) visit(size_t(o));
        state[i] = 2;
    };
    for (size_t i = 0; i < n; ++i) visit(i);
}

void parse_masks(const ordered_json &masks, const std::string &file,
                 const std::vector<std::string> &type_names, ControlSpec *spec) {
    const Fields top(file, "masks");
    if (!masks.is_array()) top.fail("", "expected an array of masks");
    auto type_index = [&](const Fields &f, const ordered_json &m,
                          const std::string &key) {
        const std::string name = f.string(m, key);
        for (size_t k = 0; k < type_names.size(); ++k)
            if (type_names[k] == name) return static_cast<int>(k);
        f.fail(key, "unknown cell type '" + name + "'");
    };
    for (size_t i = 0; i < masks.size(); ++i) {
        const Fields f(file, "masks[" + std::to_string(i) + "]");
        const ordered_json &m = masks[i];
        f.keys(m, {"type", "only_in", "not_in", "otherwise", "notes"});
        MaskSpec mask;
        mask.type = type_index(f, m, "type");
        mask.otherwise = type_index(f, m, "otherwise");
        if (mask.otherwise == mask.type)
            f.fail("otherwise", "must differ from the masked type");
        if (m.contains("only_in") == m.contains("not_in"))
            f.fail("", "give one of only_in and not_in");
        mask.inside = m.contains("only_in");
        const std::string key = mask.inside ? "only_in" : "not_in";
        const std::string region = f.string(m, key);
        mask.region = spec->find_region(region);
        if (mask.region < 0) f.fail(key, "unknown region '" + region + "'");
        spec->masks.push_back(mask);
    }
    // One pass over the masks then settles every cell: no `otherwise` is itself masked.
    for (size_t i = 0; i < spec->masks.size(); ++i)
        for (const MaskSpec &other : spec->masks)
            if (other.type == spec->masks[i].otherwise)
                top.fail("[" + std::to_string(i) + "].otherwise",
                         "'" + type_names[other.type] +
                             "' is itself masked: a masked cell must turn into a type "
                             "no mask changes");
}

LocalValue parse_local_value(const ordered_json &v, const std::string &path,
                             const std::string &file, const ControlSpec &spec,
                             ValueRange range) {
    const Fields f(file, path);
    auto checked = [&](const std::string &key, double x) {
        if (x >= range.lo && x <= range.hi && !(range.lo_open && x == range.lo)) return x;
        if (range.hi == std::numeric_limits<double>::max())
            f.fail(key, JsonFields::format(x) + ": must be " +
                            (range.lo_open ? "> " : ">= ") +
                            JsonFields::format(range.lo));
        f.fail(key, JsonFields::format(x) + ": must be in " +
                        (range.lo_open ? "(" : "[") + JsonFields::format(range.lo) +
                        ", " + JsonFields::format(range.hi) + "]");
        return x;
    };
    LocalValue out;
    if (!v.is_object()) {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            f.fail("",
                   "expected a number or {\"default\": number, \"in\": {region: "
                   "number}}");
        out.value = checked("", v.get<double>());
        return out;
    }
    f.keys(v, {"default", "in"});
    out.value = checked("default", f.number(v, "default", 0, true));
    if (!v.contains("in")) f.fail("in", "missing (or give a plain number)");
    const ordered_json &in = v["in"];
    if (!in.is_object() || in.empty())
        f.fail("in", "expected an object {region: value, ...}");
    const Fields fin(file, path + ".in");
    for (const auto &[name, value] : in.items()) {
        const int region = spec.find_region(name);
        if (region < 0)
            fin.fail(name, spec.region_names.empty()
                               ? "unknown region (the preset has no \"regions\")"
                               : "unknown region '" + name + "'");
        if (!value.is_number() || !std::isfinite(value.get<double>()))
            fin.fail(name, "expected a number");
        out.in.push_back({region, checked("in." + name, value.get<double>())});
    }
    return out;
}

}  // namespace pelage::sim
