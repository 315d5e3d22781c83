#include "renderer/scene_fur.h"

#include <cmath>
#include <set>
#include <sstream>

#include "sim/input_error.h"

namespace pelage::renderer {

namespace {

using json = nlohmann::json;

// Takes each key at most once; finish() rejects the keys nobody took.
class FurReader {
  public:
    FurReader(const json &j, std::string field, std::string file)
        : m_j(j), m_field(std::move(field)), m_file(std::move(file)) {
        if (!j.is_object()) fail(m_field, "expected an object");
    }
    [[noreturn]] void fail(const std::string &f, const std::string &msg) const {
        throw InputError(m_file, 0, f, msg);
    }
    std::string at(const std::string &key) const { return m_field + "." + key; }
    const json *take(const std::string &key) {
        m_taken.insert(key);
        const auto it = m_j.find(key);
        return it == m_j.end() ? nullptr : &*it;
    }
    double number(const json &v, const std::string &f, double lo, double hi,
                  bool open_lo = false) const {
        if (!v.is_number()) fail(f, "expected a number");
        const double x = v.get<double>();
        if (!std::isfinite(x) || x < lo || x > hi || (open_lo && x == lo)) {
            std::ostringstream s;
            s << "= " << x << ": must be in " << (open_lo ? "(" : "[") << lo << ", " << hi
              << "]";
            fail(f, s.str());
        }
        return x;
    }
    float num(const std::string &key, float def, double lo, double hi,
              bool open_lo = false) {
        const json *v = take(key);
        return v ? float(number(*v, at(key), lo, hi, open_lo)) : def;
    }
    uint64_t integer(const std::string &key, uint64_t def, uint64_t lo, uint64_t hi) {
        const json *v = take(key);
        if (!v) return def;
        if (!v->is_number_integer() ||
            (v->is_number_integer() && v->get<int64_t>() < 0 && !v->is_number_unsigned()))
            fail(at(key), "expected a non-negative integer");
        const uint64_t x = v->get<uint64_t>();
        if (x < lo || x > hi)
            fail(at(key), "= " + std::to_string(x) + ": must be in [" +
                              std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return x;
    }
    // A list of per-cell-type multipliers, each in (lo, hi] (or [0, hi] when zero_ok).
    std::vector<float> per_type(const std::string &key, bool zero_ok) {
        const json *v = take(key);
        if (!v) return {};
        if (!v->is_array() || v->empty() || v->size() > 16)
            fail(at(key), "expected an array of 1 to 16 numbers (one per cell type)");
        std::vector<float> out;
        for (size_t i = 0; i < v->size(); ++i)
            out.push_back(float(number((*v)[i], at(key) + "[" + std::to_string(i) + "]",
                                       0, 1000, !zero_ok)));
        return out;
    }
    void finish() const {
        for (auto it = m_j.begin(); it != m_j.end(); ++it)
            if (!m_taken.count(it.key())) fail(at(it.key()), "unknown field");
    }

  private:
    const json &m_j;
    std::string m_field, m_file;
    std::set<std::string> m_taken;
};

}  // namespace

fur::FurParams read_fur(const json &j, const std::string &field,
                        const std::string &scene_path) {
    FurReader r(j, field, scene_path);
    fur::FurParams p;
    if (const json *v = r.take("density"))
        p.density = r.number(*v, r.at("density"), 0, 1e12);
    p.density_by_type = r.per_type("density_by_type", true);
    if (!p.density_by_type.empty() &&
        *std::max_element(p.density_by_type.begin(), p.density_by_type.end()) <= 0)
        r.fail(r.at("density_by_type"), "every multiplier is 0: no strand could grow");
    p.seed = r.integer("seed", p.seed, 0, ~0ull);
    p.max_strands = r.integer("max_strands", p.max_strands, 1, 50'000'000);
    p.length = r.num("length", p.length, 0, 1e9, true);
    p.length_by_type = r.per_type("length_by_type", false);
    p.length_variation = r.num("length_variation", p.length_variation, 0, 0.99);
    p.root_radius = r.num("root_radius", p.root_radius, 0, 1e9, true);
    p.tip_radius = r.num("tip_radius", p.tip_radius, 0, 1e9, true);
    p.segments = int(r.integer("segments", uint64_t(p.segments), 1, 64));
    if (const json *v = r.take("comb")) {
        if (v->is_string() && v->get<std::string>() == "normal") {
            p.comb = fur::FurParams::Comb::normal;
        } else if (v->is_array() && v->size() == 3) {
            for (int k = 0; k < 3; ++k)
                (k == 0   ? p.comb_direction.x
                 : k == 1 ? p.comb_direction.y
                          : p.comb_direction.z) =
                    float(r.number((*v)[k], r.at("comb") + "[" + std::to_string(k) + "]",
                                   -1e6, 1e6));
            const fur::Vec3f c = p.comb_direction;
            if (c.x * c.x + c.y * c.y + c.z * c.z <= 0)
                r.fail(r.at("comb"), "must not be zero");
        } else {
            r.fail(r.at("comb"), "expected [x, y, z] (a world direction) or \"normal\"");
        }
    }
    p.comb_angle_deg = r.num("comb_angle", p.comb_angle_deg, 0, 90);
    p.comb_jitter_deg = r.num("comb_jitter", p.comb_jitter_deg, 0, 60);
    p.gravity = r.num("gravity", p.gravity, 0, 10);
    p.curl_radius = r.num("curl_radius", p.curl_radius, 0, 1);
    p.curl_turns = r.num("curl_turns", p.curl_turns, 0, 100);
    p.clump = r.num("clump", p.clump, 0, 1);
    p.clump_radius = r.num("clump_radius", p.clump_radius, 0, 1e9, true);
    p.melanin_scale = r.num("melanin_scale", p.melanin_scale, 0, 100);
    p.melanin_jitter = r.num("melanin_jitter", p.melanin_jitter, 0, 1);
    p.beta_m = r.num("beta_m", p.beta_m, 0, 1, true);
    p.beta_n = r.num("beta_n", p.beta_n, 0, 1, true);
    p.alpha_deg = r.num("alpha", p.alpha_deg, -44, 44);
    if (const json *v = r.take("curve")) {
        const std::string s = v->is_string() ? v->get<std::string>() : "";
        if (s == "round")
            p.curve = fur::FurParams::Curve::round;
        else if (s == "flat")
            p.curve = fur::FurParams::Curve::flat;
        else
            r.fail(r.at("curve"),
                   "expected \"round\" (B-spline tubes, close-ups) or "
                   "\"flat\" (linear ribbons, distance)");
    }
    if (p.curve == fur::FurParams::Curve::round && p.segments < 2)
        r.fail(r.at("segments"), "a round (B-spline) strand needs at least 2 segments");
    r.finish();
    return p;
}

}  // namespace pelage::renderer
