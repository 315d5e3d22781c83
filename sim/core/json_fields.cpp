#include "sim/core/json_fields.h"

#include <cmath>
#include <sstream>

#include "sim/core/colour_spelling.h"
#include "sim/core/spelling.h"

namespace pelage::sim {

JsonObjectFields::JsonObjectFields(const json &j, std::string path, std::string file)
    : JsonFields(std::move(file)), m_j(j), m_path(std::move(path)) {
    if (!j.is_object())
        fail(m_path, std::string("expected an object, got ") + json_type_name(j));
}

std::string JsonObjectFields::spelled(const std::string &key) const {
    return spelling_in(m_j, key, file(), join(m_path, key));
}

const JsonObjectFields::json *JsonObjectFields::take(const std::string &key) {
    asked(key);
    m_taken.insert(key);
    if (const std::string other = other_colour_spelling(key); !other.empty())
        m_taken.insert(other);
    const auto it = m_j.find(spelled(key));
    return it == m_j.end() ? nullptr : &*it;
}

const JsonObjectFields::json &JsonObjectFields::require(const std::string &key) {
    const json *v = take(key);
    if (!v) fail(field(key), "missing required field");
    return *v;
}

double JsonObjectFields::number(const std::string &key, double def, double lo, double hi,
                                bool required, bool open_lo) {
    const json *v = required ? &require(key) : take(key);
    return v ? check_number(*v, field(key), lo, hi, open_lo) : def;
}

int JsonObjectFields::integer(const std::string &key, int def, long lo, long hi) {
    const json *v = take(key);
    if (!v) return def;
    if (!v->is_number_integer())
        fail(field(key), std::string("expected an integer, got ") + json_type_name(*v));
    const long x = v->get<long>();
    if (x < lo || x > hi)
        fail(field(key), "= " + std::to_string(x) + ": must be in [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return int(x);
}

uint64_t JsonObjectFields::unsigned_integer(const std::string &key, uint64_t def,
                                            uint64_t lo, uint64_t hi) {
    const json *v = take(key);
    if (!v) return def;
    if (!v->is_number_unsigned() && !(v->is_number_integer() && v->get<int64_t>() >= 0))
        fail(field(key),
             std::string("expected a non-negative integer, got ") +
                 (v->is_number_integer() ? "a negative one" : json_type_name(*v)));
    const uint64_t x = v->get<uint64_t>();
    if (x < lo || x > hi)
        fail(field(key), "= " + std::to_string(x) + ": must be in [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return x;
}

bool JsonObjectFields::boolean(const std::string &key, bool def) {
    const json *v = take(key);
    if (!v) return def;
    if (!v->is_boolean())
        fail(field(key),
             std::string("expected true or false, got ") + json_type_name(*v));
    return v->get<bool>();
}

std::string JsonObjectFields::string(const std::string &key, const std::string &def,
                                     bool required) {
    const json *v = required ? &require(key) : take(key);
    if (!v) return def;
    if (!v->is_string())
        fail(field(key), std::string("expected a string, got ") + json_type_name(*v));
    return v->get<std::string>();
}

Vec3f JsonObjectFields::vec3(const std::string &key, Vec3f def, double lo, double hi,
                             bool required) {
    const json *v = required ? &require(key) : take(key);
    return v ? check_vec3(*v, field(key), lo, hi) : def;
}

Rgb JsonObjectFields::color(const std::string &key, Rgb def, double hi) {
    const json *v = take(key);
    if (!v) return def;
    if (v->is_number()) {
        const float x = float(check_number(*v, field(key), 0, hi));
        return {x, x, x};
    }
    return check_vec3(*v, field(key), 0, hi);
}

double JsonObjectFields::check_number(const json &v, const std::string &f, double lo,
                                      double hi, bool open_lo) const {
    if (!v.is_number())
        fail(f, std::string("expected a number, got ") + json_type_name(v));
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi || (open_lo && x == lo)) {
        std::ostringstream s;
        s << "= " << x << ": must be in " << (open_lo ? "(" : "[") << lo << ", " << hi
          << "]";
        fail(f, s.str());
    }
    return x;
}

Vec3f JsonObjectFields::check_vec3(const json &v, const std::string &f, double lo,
                                   double hi) const {
    if (!v.is_array() || v.size() != 3)
        fail(f, std::string("expected an array of 3 numbers, got ") + json_type_name(v) +
                    (v.is_array() ? " of " + std::to_string(v.size()) : std::string()));
    return {float(check_number(v[0], f + "[0]", lo, hi)),
            float(check_number(v[1], f + "[1]", lo, hi)),
            float(check_number(v[2], f + "[2]", lo, hi))};
}

std::vector<std::string> JsonObjectFields::known_keys() const {
    return {m_taken.begin(), m_taken.end()};
}

void JsonObjectFields::finish() const {
    for (auto it = m_j.begin(); it != m_j.end(); ++it) {
        if (m_taken.count(it.key())) continue;
        const std::string guess = closest_name(it.key(), known_keys());
        fail(field(it.key()), guess.empty()
                                  ? "unknown field"
                                  : "unknown field (did you mean \"" + guess + "\"?)");
    }
}

}  // namespace pelage::sim
