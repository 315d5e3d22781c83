// Reading a plugin's parameters by name, against the plugin's own table.
//
// The renderer hands create() one value per table entry, in table order; reading them by
// position (values[6].i) silently reads the wrong one when the table changes. Params
// looks a name up in the table, checks that the type asked for is the table's and that
// the set carries that value with that type, and throws ParamError otherwise. Under
// guarded_create (create_guard.h) that error is create()'s refusal, so a misspelt name
// or a wrong getter shows up the first time the plugin is used.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shader/pelage_shader.h"

namespace pelage::shader::sdk {

// A parameter read that disagrees with the plugin's table: a bug in the plugin.
class ParamError : public std::logic_error {
  public:
    using std::logic_error::logic_error;
};

inline const char *type_name(PelageParamType t) {
    switch (t) {
        case PELAGE_PARAM_FLOAT:
            return "float";
        case PELAGE_PARAM_INT:
            return "int";
        case PELAGE_PARAM_RGB:
            return "rgb";
        case PELAGE_PARAM_STRING:
            return "string";
    }
    return "unknown type";
}

// The entry of a {0}-terminated table called `name`, or null.
inline const PelageParamSpec *find_spec(const PelageParamSpec *table,
                                        std::string_view name) {
    for (const PelageParamSpec *s = table; s && s->name; ++s)
        if (name == s->name) return s;
    return nullptr;
}

class Params {
  public:
    // `table`: the plugin's own {0}-terminated table; `set`: what create() received.
    // Both must outlive this object.
    Params(const PelageParamSpec *table, const PelageParamSet &set)
        : m_table(table), m_set(set) {
        if (!table) throw ParamError("the plugin has no parameter table");
    }

    float get_float(std::string_view name) const {
        return value(name, PELAGE_PARAM_FLOAT).f[0];
    }
    int32_t get_int(std::string_view name) const {
        return value(name, PELAGE_PARAM_INT).i;
    }
    // An INT parameter used as a switch: anything but 0 is on.
    bool get_bool(std::string_view name) const { return get_int(name) != 0; }
    std::array<float, 3> get_rgb(std::string_view name) const {
        const PelageParamValue &v = value(name, PELAGE_PARAM_RGB);
        return {v.f[0], v.f[1], v.f[2]};
    }
    // A null string in the set reads as "".
    std::string get_string(std::string_view name) const {
        const char *s = value(name, PELAGE_PARAM_STRING).s;
        return s ? s : "";
    }

    const PelageParamSet &set() const { return m_set; }

  private:
    const PelageParamValue &value(std::string_view name, PelageParamType type) const {
        const PelageParamSpec *spec = find_spec(m_table, name);
        if (!spec)
            throw ParamError("parameter \"" + std::string(name) +
                             "\" is not in the plugin's table");
        if (spec->type != type)
            throw ParamError("parameter \"" + std::string(name) + "\" is " +
                             type_name(spec->type) + " in the plugin's table, read as " +
                             type_name(type));
        // The set is in table order: the value is normally at the entry's index.
        const size_t k = size_t(spec - m_table);
        const PelageParamValue *v = nullptr;
        if (k < m_set.count && m_set.values[k].name && name == m_set.values[k].name)
            v = &m_set.values[k];
        for (uint32_t i = 0; !v && i < m_set.count; ++i)
            if (m_set.values[i].name && name == m_set.values[i].name)
                v = &m_set.values[i];
        if (!v)
            throw ParamError("parameter \"" + std::string(name) +
                             "\" has no value in the parameter set");
        if (v->type != type)
            throw ParamError("parameter \"" + std::string(name) + "\" is " +
                             type_name(type) + " in the plugin's table, " +
                             type_name(v->type) + " in the parameter set");
        return *v;
    }

    const PelageParamSpec *m_table;
    const PelageParamSet &m_set;
};

}  // namespace pelage::shader::sdk
