// Reading the fields of a JSON preset block: every error is an InputError naming the
// file and the JSON path of the offending value, unknown keys are errors (never
// warn-and-ignore), and numbers must be finite. The preset parsers (cell types, growth,
// fields, spatial control) build their own checks (ranges, matrices, directions) on
// these primitives, so one mistake reads the same in every block.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sim/core/input_error.h"
#include "sim/core/vec.h"

namespace pelage::sim {

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

}  // namespace pelage::sim
