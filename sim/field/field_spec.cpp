#include "sim/field/field_spec.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "sim/core/input_error.h"
#include "sim/core/json_fields.h"
#include "sim/crps/body_length.h"
#include "sim/field/vector_heat.h"

namespace pelage::sim {

using nlohmann::json;

namespace {

// The field block's fields (sim/core/json_fields.h) and directions.
class Parser : public JsonFields {
  public:
    using JsonFields::JsonFields;

    Vec3d direction(const json &v, const std::string &path) const {
        const Vec3d d = vec3(v, path);
        if (!(length(d) > 0)) fail(path, "must not be the zero vector");
        return normalize(d);
    }
};

Vec2d closest_in_triangle(const std::array<Vec2d, 3> &v, Vec2d p) {
    // Inside (all edge functions of one sign): p itself; else the nearest edge point.
    const double s = cross(v[1] - v[0], v[2] - v[0]);
    bool inside = true;
    for (int k = 0; k < 3; ++k)
        inside = inside && cross(v[(k + 1) % 3] - v[k], p - v[k]) * s >= 0;
    if (inside) return p;
    Vec2d best = v[0];
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const Vec2d a = v[k], e = v[(k + 1) % 3] - a;
        const double l2 = length_squared(e);
        const double u = l2 > 0 ? std::clamp(dot(p - a, e) / l2, 0.0, 1.0) : 0.0;
        const Vec2d q = a + e * u;
        if (const double d2 = length_squared(p - q); d2 < best_d2) best_d2 = d2, best = q;
    }
    return best;
}

}  // namespace

FieldSpec parse_field_spec(const json &node, const std::string &path,
                           const std::string &file) {
    const Parser r(file);
    r.check_keys(node, path,
                 {"direction", "along", "around", "controls", "space", "interpolation",
                  "diffusion_time"});
    FieldSpec spec;
    const int kinds = node.contains("direction") + node.contains("along") +
                      node.contains("around") + node.contains("controls");
    if (kinds != 1)
        r.fail(path,
               "give exactly one of \"direction\", \"along\", \"around\" or "
               "\"controls\"");
    if (!node.contains("controls"))
        for (const char *key : {"space", "interpolation", "diffusion_time"})
            if (node.contains(key)) r.fail(path + "." + key, "only with \"controls\"");
    if (node.contains("direction")) {
        spec.kind = FieldSpec::Kind::direction;
        spec.direction = r.direction(node["direction"], path + ".direction");
    }
    for (const char *key : {"along", "around"}) {
        if (!node.contains(key)) continue;
        const std::string axis = r.string(node[key], path + "." + key);
        if (axis != "body_axis")
            r.fail(path + "." + key, "'" + axis + "': expected \"body_axis\"");
        spec.kind = std::string(key) == "along" ? FieldSpec::Kind::along_body_axis
                                                : FieldSpec::Kind::around_body_axis;
    }
    if (node.contains("controls")) {
        spec.kind = FieldSpec::Kind::controls;
        const json &c = node["controls"];
        const std::string cpath = path + ".controls";
        if (!c.is_array() || c.empty() || c.size() > 10000)
            r.fail(cpath, "expected an array of 1 to 10000 {\"at\", \"direction\"}");
        for (size_t i = 0; i < c.size(); ++i) {
            const std::string p = cpath + "[" + std::to_string(i) + "]";
            r.check_keys(c[i], p, {"at", "direction"});
            if (!c[i].contains("at")) r.fail(p + ".at", "missing");
            if (!c[i].contains("direction")) r.fail(p + ".direction", "missing");
            spec.controls.push_back({r.vec3(c[i]["at"], p + ".at"),
                                     r.direction(c[i]["direction"], p + ".direction")});
        }
        if (node.contains("space")) {
            const std::string space = r.string(node["space"], path + ".space");
            if (space != "box" && space != "world")
                r.fail(path + ".space", "'" + space + "': expected \"box\" or \"world\"");
            spec.box_space = space == "box";
        }
        if (node.contains("interpolation")) {
            const std::string how =
                r.string(node["interpolation"], path + ".interpolation");
            if (how != "harmonic" && how != "heat")
                r.fail(path + ".interpolation",
                       "'" + how + "': expected \"harmonic\" or \"heat\"");
            spec.heat = how == "heat";
        }
        if (node.contains("diffusion_time")) {
            if (!spec.heat)
                r.fail(path + ".diffusion_time", "only with \"interpolation\": \"heat\"");
            const json &t = node["diffusion_time"];
            if (!t.is_number() || !(t.get<double>() > 0) || !(t.get<double>() <= 1e6))
                r.fail(path + ".diffusion_time", "expected a number in (0, 1e6]");
            spec.diffusion_time = t.get<double>();
        }
    }
    return spec;
}

NearestPoint nearest_surface_point(const Crps &crps, Vec3d p) {
    NearestPoint best;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (TriId t = 0; t < crps.num_triangles(); ++t) {
        const CrpsFrame &f = crps.frame(t);
        const double off = (f.rotation * p).y - f.y_offset;
        if (off * off >= best_d2) continue;
        const Vec2d q = crps.to_2d(t, p);
        const Vec2d c = closest_in_triangle(f.v, q);
        const double d2 = off * off + length_squared(q - c);
        if (d2 < best_d2) {
            best_d2 = d2;
            best.tri = t;
            best.barycentric = crps.to_barycentric(t, c);
        }
    }
    best.distance = std::sqrt(best_d2);
    return best;
}

TangentField resolve_field(const FieldSpec &spec, const Crps &crps, double magnitude) {
    const size_t nt = crps.num_triangles();
    switch (spec.kind) {
        case FieldSpec::Kind::none:
            return {};
        case FieldSpec::Kind::direction:
            return constant_world_field(
                crps, {spec.direction.x, spec.direction.y, spec.direction.z}, magnitude);
        case FieldSpec::Kind::along_body_axis:
        case FieldSpec::Kind::around_body_axis: {
            const BodyAxis axis = body_axis(crps);
            const bool around = spec.kind == FieldSpec::Kind::around_body_axis;
            TangentField field;
            field.a.assign(nt, Vec2d{});
            for (TriId t = 0; t < nt; ++t) {
                const Vec3d d =
                    around ? cross(axis.axis, crps.to_3d(t, {0, 0}) - axis.centroid)
                           : axis.axis;
                const Vec2d p = world_to_field(crps, t, d);
                const double len = length(p), full = length(d);
                // Below 1e-6 of its length the direction is normal to the triangle (or,
                // around the axis, the centroid lies on it): no preferred axis.
                if (len > 1e-6 * full && len > 0) field.a[t] = p * (magnitude / len);
            }
            return field;
        }
        case FieldSpec::Kind::controls: {
            Bounds3 box;
            for (TriId t = 0; t < nt; ++t)
                for (const Vec2d &v : crps.frame(t).v) box.extend(crps.to_3d(t, v));
            std::vector<TangentControl> controls;
            for (size_t i = 0; i < spec.controls.size(); ++i) {
                const FieldControl &c = spec.controls[i];
                const Vec3d at = spec.box_space
                                     ? Vec3d{box.lo.x + c.at.x * (box.hi.x - box.lo.x),
                                             box.lo.y + c.at.y * (box.hi.y - box.lo.y),
                                             box.lo.z + c.at.z * (box.hi.z - box.lo.z)}
                                     : c.at;
                const NearestPoint q = nearest_surface_point(crps, at);
                // The direction projected into the triangle's plane.
                const Vec3d n = crps.frame(q.tri).normal;
                const Vec3d d = c.direction - n * dot(c.direction, n);
                if (!(length(d) > 1e-6))
                    throw InputError(
                        "", 0,
                        "simulation.anisotropy.field.controls[" + std::to_string(i) +
                            "].direction",
                        "normal to the surface at the control's point (triangle " +
                            std::to_string(q.tri) + "): no tangent direction");
                controls.push_back({q.tri, q.barycentric, d});
            }
            FieldInterpolation how;
            how.method = spec.heat ? FieldInterpolation::Method::heat
                                   : FieldInterpolation::Method::harmonic;
            how.time_scale = spec.diffusion_time;
            return vector_heat_field(crps, controls, magnitude, how);
        }
    }
    return {};
}

}  // namespace pelage::sim
