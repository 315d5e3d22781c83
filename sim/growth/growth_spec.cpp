#include "sim/growth/growth_spec.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"

namespace pelage::sim {

using nlohmann::json;

namespace {

// The growth block's fields (sim/core/json_fields.h), positive numbers and points.
class Reader : public JsonFields {
  public:
    using JsonFields::JsonFields;

    double positive(const json &v, const std::string &path) const {
        const double d = number(v, path);
        if (!(d > 0)) fail(path, "must be > 0");
        return d;
    }
    // Each coordinate is checked at its own index, unlike JsonFields::vec3.
    Vec3d point(const json &v, const std::string &path) const {
        if (!v.is_array() || v.size() != 3) fail(path, "expected [x, y, z]");
        return {number(v[0], path + "[0]"), number(v[1], path + "[1]"),
                number(v[2], path + "[2]")};
    }
};

std::vector<GrowthCylinder> parse_cylinders(const Reader &r, const json &v,
                                            const std::string &path) {
    if (!v.is_array()) r.fail(path, "expected an array of cylinders");
    std::vector<GrowthCylinder> out;
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string p = path + "[" + std::to_string(i) + "]";
        const json &c = v[i];
        r.check_keys(c, p, {"name", "from", "to", "radius", "parent"});
        for (const char *k : {"name", "from", "to", "radius"})
            if (!c.contains(k)) r.fail(p + "." + k, "missing");
        GrowthCylinder cyl;
        cyl.name = r.non_empty_string(c["name"], p + ".name");
        for (const GrowthCylinder &o : out)
            if (o.name == cyl.name)
                r.fail(p + ".name", "'" + cyl.name + "' is used twice");
        cyl.from = r.point(c["from"], p + ".from");
        cyl.to = r.point(c["to"], p + ".to");
        if (!(length(cyl.to - cyl.from) > 0)) r.fail(p + ".to", "equals from: no axis");
        cyl.radius = r.positive(c["radius"], p + ".radius");
        if (c.contains("parent")) {
            const std::string parent = r.non_empty_string(c["parent"], p + ".parent");
            for (size_t k = 0; k < out.size(); ++k)
                if (out[k].name == parent) cyl.parent = int(k);
            if (cyl.parent < 0)
                r.fail(p + ".parent",
                       "'" + parent + "' is not a cylinder listed before this one");
        }
        out.push_back(cyl);
    }
    return out;
}

GrowthKey parse_key(const Reader &r, const json &k, const std::string &p,
                    const std::vector<GrowthCylinder> &cylinders,
                    const std::string &base_dir) {
    r.check_keys(k, p, {"age", "scale", "mesh", "cylinders"});
    GrowthKey key;
    key.path = p;
    if (!k.contains("age")) r.fail(p + ".age", "missing");
    key.age = r.number(k["age"], p + ".age");
    const int kinds =
        int(k.contains("scale")) + int(k.contains("mesh")) + int(k.contains("cylinders"));
    if (kinds != 1)
        r.fail(p, kinds == 0 ? "give the shape: one of scale, mesh or cylinders"
                             : "give one of scale, mesh or cylinders, not several");
    if (k.contains("scale")) {
        key.kind = GrowthKey::Kind::scale;
        key.scale = r.positive(k["scale"], p + ".scale");
    } else if (k.contains("mesh")) {
        key.kind = GrowthKey::Kind::mesh;
        const std::string m = r.non_empty_string(k["mesh"], p + ".mesh");
        const std::filesystem::path mp(m);
        key.mesh =
            mp.is_absolute() || base_dir.empty()
                ? m
                : (std::filesystem::path(base_dir) / mp).lexically_normal().string();
    } else {
        key.kind = GrowthKey::Kind::cylinders;
        const std::string cp = p + ".cylinders";
        if (cylinders.empty()) r.fail(cp, "growth.cylinders defines no cylinder");
        if (!k["cylinders"].is_object()) r.fail(cp, "expected an object");
        key.cylinder_scales.assign(cylinders.size(), {1.0, 1.0});
        for (const auto &[name, value] : k["cylinders"].items()) {
            const std::string np = cp + "." + name;
            int index = -1;
            for (size_t i = 0; i < cylinders.size(); ++i)
                if (cylinders[i].name == name) index = int(i);
            if (index < 0) r.fail(np, "no cylinder of that name in growth.cylinders");
            r.check_keys(value, np, {"length", "radius"});
            if (value.contains("length"))
                key.cylinder_scales[index][0] =
                    r.positive(value["length"], np + ".length");
            if (value.contains("radius"))
                key.cylinder_scales[index][1] =
                    r.positive(value["radius"], np + ".radius");
        }
    }
    return key;
}

}  // namespace

bool GrowthSpec::has_mesh_keys() const {
    for (const GrowthKey &k : keys)
        if (k.kind == GrowthKey::Kind::mesh) return true;
    return false;
}

GrowthSpec parse_growth(const json &node, const std::string &path,
                        const std::string &file, const std::string &base_dir) {
    const Reader r(file);
    r.check_keys(node, path,
                 {"keys", "interpolation", "interval", "cylinders", "pattern"});
    GrowthSpec spec;
    spec.file = file;
    if (node.contains("interpolation")) {
        const std::string s =
            r.non_empty_string(node["interpolation"], path + ".interpolation");
        if (s == "linear")
            spec.interpolation = GrowthInterpolation::linear;
        else if (s == "smooth")
            spec.interpolation = GrowthInterpolation::smooth;
        else
            r.fail(path + ".interpolation",
                   "'" + s + "' is not one of \"linear\", \"smooth\"");
    }
    if (node.contains("pattern")) {
        const std::string s = r.non_empty_string(node["pattern"], path + ".pattern");
        if (s != "during_growth" && s != "before_growth")
            r.fail(path + ".pattern",
                   "'" + s + "' is not one of \"during_growth\", \"before_growth\"");
        spec.during = s == "during_growth";
    }
    if (node.contains("interval"))
        spec.interval = r.positive(node["interval"], path + ".interval");
    if (node.contains("cylinders"))
        spec.cylinders = parse_cylinders(r, node["cylinders"], path + ".cylinders");
    if (!node.contains("keys")) r.fail(path + ".keys", "missing");
    const json &keys = node["keys"];
    if (!keys.is_array() || keys.empty())
        r.fail(path + ".keys", "expected a non-empty array of {\"age\": ..., ...}");
    for (size_t i = 0; i < keys.size(); ++i) {
        const std::string p = path + ".keys[" + std::to_string(i) + "]";
        spec.keys.push_back(parse_key(r, keys[i], p, spec.cylinders, base_dir));
        if (i > 0 && !(spec.keys[i].age > spec.keys[i - 1].age))
            r.fail(p + ".age", "ages must increase from key to key");
    }
    return spec;
}

}  // namespace pelage::sim

namespace pelage::sim {

GrowthSpec load_growth(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open preset file");
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception &e) {
        throw InputError(path, 0, "", std::string("not valid JSON: ") + e.what());
    }
    if (!j.is_object() || !j.contains("growth"))
        throw InputError(path, 0, "growth", "missing: the preset has no growth block");
    return parse_growth(j["growth"], "growth", path,
                        std::filesystem::path(path).parent_path().string());
}

}  // namespace pelage::sim
