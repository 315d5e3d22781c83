// Reading the fields of JSON input: every error is an InputError naming the file and
// the JSON path of the offending value, unknown keys are errors (never warn-and-ignore),
// and numbers must be finite. The preset parsers (cell types, growth, fields, spatial
// control) build their own checks (ranges, matrices, directions) on JsonFields'
// primitives, so one mistake reads the same in every block. The scene file reads each
// of its objects through JsonObjectFields, the same reader bound to one object.
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/input_error.h"
#include "sim/core/vec.h"

namespace pelage::sim {

// "a string", "an array", ...: what a value is, for messages.
template <class Json>
const char *json_type_name(const Json &j) {
    switch (j.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::string:
            return "a string";
        case Json::value_t::array:
            return "an array";
        case Json::value_t::object:
            return "an object";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
            return "an integer";
        case Json::value_t::number_float:
            return "a number";
        default:
            return "an unknown value";
    }
}

// Works on nlohmann::json and nlohmann::ordered_json alike (the `Json` parameter).
class JsonFields {
  public:
    explicit JsonFields(std::string file) : m_file(std::move(file)) {}

    const std::string &file() const { return m_file; }

    [[noreturn]] void fail(const std::string &path, const std::string &message) const {
        throw InputError(m_file, 0, path, message);
    }

    // `path.key`, or `key` at the top level (empty `path`).
    static std::string join(const std::string &path, const std::string &key) {
        return path.empty() ? key : path + "." + key;
    }

    // A number as error messages print it (std::ostream's default: "0.5", "1e+06").
    static std::string format(double v) {
        std::ostringstream s;
        s << v;
        return s.str();
    }

    // `obj` is an object whose keys are all in `allowed`.
    template <class Json>
    void check_keys(const Json &obj, const std::string &path,
                    const std::set<std::string> &allowed) const {
        if (!obj.is_object())
            fail(path.empty() ? "(top level)" : path, "expected an object");
        for (const auto &[key, value] : obj.items())
            if (!allowed.count(key)) fail(join(path, key), "unknown key");
    }

    // `v` is a finite number.
    template <class Json>
    double number(const Json &v, const std::string &path) const {
        if (!v.is_number()) fail(path, "expected a number");
        const double d = v.template get<double>();
        if (!std::isfinite(d)) fail(path, "expected a finite number");
        return d;
    }

    // obj[key], or nullptr when `obj` has no `key`; absent and `required` is an error.
    template <class Json>
    const Json *find(const Json &obj, const std::string &path, const std::string &key,
                     bool required) const {
        const auto it = obj.find(key);
        if (it != obj.end()) return &*it;
        if (required) fail(join(path, key), "missing");
        return nullptr;
    }

    // obj[key] as a finite number; `fallback` when absent, unless `required`.
    template <class Json>
    double number(const Json &obj, const std::string &path, const std::string &key,
                  double fallback, bool required = false) const {
        const Json *v = find(obj, path, key, required);
        return v ? number(*v, join(path, key)) : fallback;
    }

    // `v` is an array of `n` finite numbers. A non-finite one is reported at its index as
    // "not finite", or, given `not_finite`, at `path` with that message.
    template <class Json>
    std::vector<double> numbers(const Json &v, const std::string &path, size_t n,
                                const char *not_finite = nullptr) const {
        if (!v.is_array() || v.size() != n)
            fail(path, "expected " + std::to_string(n) + " numbers");
        std::vector<double> out;
        for (size_t i = 0; i < n; ++i) {
            if (!v[i].is_number())
                fail(path, "expected " + std::to_string(n) + " numbers");
            out.push_back(v[i].template get<double>());
            if (std::isfinite(out.back())) continue;
            if (not_finite) fail(path, not_finite);
            fail(path + "[" + std::to_string(i) + "]", "not finite");
        }
        return out;
    }

    // `v` is an array of 3 finite numbers.
    template <class Json>
    Vec3d vec3(const Json &v, const std::string &path) const {
        const std::vector<double> c = numbers(v, path, 3);
        return {c[0], c[1], c[2]};
    }

    // `v` is a string.
    template <class Json>
    std::string string(const Json &v, const std::string &path) const {
        if (!v.is_string()) fail(path, "expected a string");
        return v.template get<std::string>();
    }

    // obj[key] as a string; `fallback` when absent, unless `required`.
    template <class Json>
    std::string string(const Json &obj, const std::string &path, const std::string &key,
                       const std::string &fallback, bool required = false) const {
        const Json *v = find(obj, path, key, required);
        return v ? string(*v, join(path, key)) : fallback;
    }

    // `v` is a string of at least one character.
    template <class Json>
    std::string non_empty_string(const Json &v, const std::string &path) const {
        if (!v.is_string() || v.template get<std::string>().empty())
            fail(path, "expected a non-empty string");
        return v.template get<std::string>();
    }

  private:
    std::string m_file;
};

// One JSON object read field by field (the scene file's camera, lights, objects...):
// every field is taken at most once, typed and range-checked, and finish() rejects the
// keys nobody took. A key holding "colour" is found in either spelling, "colour" or
// "color" (colour_spelling.h), and named in messages as the file spells it. Messages
// say what was found instead ("objects[0].fur.length = -1: must be in (0, 1e+09]",
// "film.width: expected an integer, got a string").
class JsonObjectFields : public JsonFields {
  public:
    // Document order, so errors name the first bad key as written and order-dependent
    // values (local values' regions) apply in it.
    using json = nlohmann::ordered_json;

    // `path` is the object's JSON path ("" at the top level), `file` the input file.
    JsonObjectFields(const json &j, std::string path, std::string file);
    // The reader keeps a reference: no temporaries (a nlohmann::json converted to
    // ordered_json would be one).
    JsonObjectFields(json &&, std::string, std::string) = delete;

    // The JSON path of one of this object's keys, spelled as in the file.
    std::string field(const std::string &key) const { return join(m_path, spelled(key)); }
    // `key` as the object spells it (colour or color); `key` when absent.
    std::string spelled(const std::string &key) const;
    const std::string &path_prefix() const { return m_path; }

    bool has(const std::string &key) const { return m_j.contains(spelled(key)); }
    // The key's value (nullptr when absent), marked as known either way.
    const json *take(const std::string &key);
    const json &require(const std::string &key);

    // A finite number in [lo, hi], or in (lo, hi] when open_lo.
    double number(const std::string &key, double def, double lo, double hi,
                  bool required = false, bool open_lo = false);
    int integer(const std::string &key, int def, long lo, long hi);
    uint64_t unsigned_integer(const std::string &key, uint64_t def, uint64_t lo,
                              uint64_t hi);
    bool boolean(const std::string &key, bool def);
    std::string string(const std::string &key, const std::string &def,
                       bool required = false);
    template <typename E>
    E choice(const std::string &key, E def,
             const std::vector<std::pair<std::string, E>> &options) {
        const json *v = take(key);
        if (!v) return def;
        if (!v->is_string())
            fail(field(key), std::string("expected a string, got ") + json_type_name(*v));
        const std::string s = v->get<std::string>();
        std::string all;
        for (const auto &[name, e] : options) {
            if (name == s) return e;
            all += (all.empty() ? "" : ", ") + name;
        }
        fail(field(key), "unknown value \"" + s + "\" (expected one of " + all + ")");
    }
    Vec3f vec3(const std::string &key, Vec3f def, double lo = -1e30, double hi = 1e30,
               bool required = false);
    // A colour: [r, g, b] or one number for grey, each in [0, hi].
    Rgb color(const std::string &key, Rgb def, double hi = 1e30);

    // Checks of a value found elsewhere (an array element); `f` is its JSON path.
    double check_number(const json &v, const std::string &f, double lo, double hi,
                        bool open_lo = false) const;
    Vec3f check_vec3(const json &v, const std::string &f, double lo, double hi) const;

    // Rejects every key not taken, suggesting the closest of the keys asked for.
    void finish() const;

    virtual ~JsonObjectFields() = default;
    JsonObjectFields(const JsonObjectFields &) = default;
    JsonObjectFields(JsonObjectFields &&) = default;

  protected:
    // Called by take() with every key asked for: a format that declares its fields
    // (renderer/scene_file/scene_fields.h) refuses here to read an undeclared one.
    virtual void asked(const std::string &key) const { (void)key; }
    // The keys an unknown one may be a misspelling of: by default, those asked for.
    virtual std::vector<std::string> known_keys() const;

  private:
    const json &m_j;
    std::string m_path;
    std::set<std::string> m_taken;
};

}  // namespace pelage::sim
