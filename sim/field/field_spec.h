// The anisotropy field of a preset, `simulation.anisotropy.field` (docs/guide/
// growth-and-control.md, "Vector fields"): what the preset says, independent of any mesh,
// and its resolution onto a simulation surface as one vector per triangle (TangentField).
//   {"direction": [x, y, z]}            a world direction projected into every triangle
//   {"along": "body_axis"}              the body's principal axis
//   (sim/crps/body_length.h)
//   {"around": "body_axis"}             circles about that axis (a zebra's body stripes)
//   {"controls": [{"at": [x, y, z], "direction": [x, y, z]}, ...], "space": "box"}
//                                       control vectors interpolated by the vector heat
//                                       method (vector_heat.h); points in fractions of
//                                       the bounding box ("box") or world units
//                                       ("world"), snapped to the nearest surface point;
//                                       directions are world directions projected into
//                                       the triangle; "interpolation": "harmonic" (the
//                                       smoothest field, default) or "heat" (with
//                                       "diffusion_time" in h²)
// Like the SG01 anisotropy vector A, a field's vectors all have the anisotropy magnitude.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "sim/crps/crps.h"
#include "sim/crps/tangent_field.h"

namespace pelage::sim {

struct FieldControl {
    Vec3d at, direction;
};

struct FieldSpec {
    enum class Kind { none, direction, along_body_axis, around_body_axis, controls };
    Kind kind = Kind::none;
    Vec3d direction;                     // Kind::direction (unit)
    std::vector<FieldControl> controls;  // Kind::controls
    bool box_space = true;               // controls' points: bounding-box fractions
    bool heat = false;                   // controls: "interpolation": "heat"
    double diffusion_time = 1;           // heat: t in units of h²
    bool operator==(const FieldSpec &) const = default;
};

// Parses the JSON object at `path` (e.g. "simulation.anisotropy.field"); InputError
// naming `file` and the offending JSON path.
FieldSpec parse_field_spec(const nlohmann::json &node, const std::string &path,
                           const std::string &file);

// The field on a surface, every vector of length `magnitude` (zero where undefined).
TangentField resolve_field(const FieldSpec &spec, const Crps &crps, double magnitude);

// The surface point nearest to p: its triangle and barycentric coordinates (brute force
// over the triangles, ties to the lowest triangle id).
struct NearestPoint {
    TriId tri = 0;
    Vec3d barycentric;
    double distance = 0;
};
NearestPoint nearest_surface_point(const Crps &crps, Vec3d p);

}  // namespace pelage::sim
