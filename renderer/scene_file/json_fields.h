// One JSON object of a scene file being read (scene_file.cpp, scene_fur.cpp): every field
// is taken at most once, typed and range-checked, and finish() rejects the keys nobody
// took — unknown or misspelled fields are errors, never warnings. Every
// failure is a pelage::InputError naming the file and the field's JSON path
// ("objects[0].fur.length = -1: must be in (0, 1e+09]"). A key holding "colour" is
// found in either spelling, "colour" or "color" (sim/core/colour_spelling.h), and named
// in messages as the file spells it.
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "renderer/core/math.h"

namespace pelage::renderer {

// "a string", "an array", ...: for messages.
const char *json_type_name(const nlohmann::json &j);

class JsonFields {
  public:
    using json = nlohmann::json;

    // `path` is the object's JSON path ("" at the top level), `file` the scene file.
    JsonFields(const json &j, std::string path, std::string file);

    [[noreturn]] void fail(const std::string &field, const std::string &message) const;
    // The JSON path of one of this object's keys, spelled as in the file.
    std::string field(const std::string &key) const { return join(spelled(key)); }
    // `key` as the object spells it (colour or color); `key` when absent.
    std::string spelled(const std::string &key) const;
    const std::string &path_prefix() const { return m_path; }
    const std::string &file() const { return m_file; }

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

    // Rejects every key not taken.
    void finish() const;

  private:
    std::string join(const std::string &key) const {
        return m_path.empty() ? key : m_path + "." + key;
    }
    const json &m_j;
    std::string m_path, m_file;
    std::set<std::string> m_taken;
};

}  // namespace pelage::renderer
