// Tangent fields from control vectors (sim/field/vector_heat.h) and the preset's field
// specifications (sim/field/field_spec.h), against analytic fields: a constant field on
// a plane, the axial and circumferential fields of a cylinder (both parallel), and on a
// sphere the parallel transport of the control along great circles, the short-time
// limit of the vector heat flow (Sharp, Soliman, Crane 2019).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/field/field_spec.h"
#include "sim/field/vector_heat.h"
#include "sim/mesh/procedural_mesh.h"

namespace pelage::sim {
namespace {

constexpr double deg = 180.0 / 3.14159265358979323846;

double angle_deg(Vec3d a, Vec3d b) {
    return std::atan2(length(cross(a, b)), dot(a, b)) * deg;
}
// Angle between two axes (sign ignored), in [0, 90].
double axis_angle_deg(Vec3d a, Vec3d b) {
    const double x = angle_deg(a, b);
    return std::min(x, 180 - x);
}
Vec3d centroid(const Crps &crps, TriId t) { return crps.to_3d(t, {0, 0}); }
// d projected into t's plane.
Vec3d in_plane(const Crps &crps, TriId t, Vec3d d) {
    const Vec3d n = crps.frame(t).normal;
    return d - n * dot(d, n);
}
const FieldInterpolation heat{FieldInterpolation::Method::heat, 1.0};
const FieldInterpolation harmonic{FieldInterpolation::Method::harmonic, 1.0};

TangentControl control_at(const Crps &crps, Vec3d p, Vec3d d) {
    const NearestPoint q = nearest_surface_point(crps, p);
    const Vec3d n = crps.frame(q.tri).normal;
    return {q.tri, q.barycentric, d - n * dot(d, n)};
}

TEST(VectorField, OneControlOnAPlaneGivesAConstantField) {
    const Surface s = build_surface(make_plane(16, 12, 2.0, 1.5));
    const Vec3d d = normalize(Vec3d{1, 0, 2});
    for (const FieldInterpolation &how : {heat, harmonic}) {
        const TangentField f =
            vector_heat_field(s.crps, {control_at(s.crps, {0.3, 0, -0.2}, d)}, 2.0, how);
        ASSERT_EQ(f.a.size(), s.crps.num_triangles());
        for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
            EXPECT_NEAR(length(f.a[t]), 2.0, 1e-9);
            EXPECT_LT(angle_deg(field_to_world(s.crps, t, f.a[t]), d), 1e-6) << t;
        }
    }
}

TEST(VectorField, AStripManyHundredRingsLongIsReachedEverywhere) {
    // The heat decays per ring; far from the control it would underflow at t = h².
    const Surface s = build_surface(make_plane(900, 1, 900.0, 1.0));
    const Vec3d d{0, 0, 1};
    const TangentField f =
        vector_heat_field(s.crps, {control_at(s.crps, {-449.5, 0, 0}, d)}, 1.0, heat);
    for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
        ASSERT_NEAR(length(f.a[t]), 1.0, 1e-9) << t;
        EXPECT_LT(angle_deg(field_to_world(s.crps, t, f.a[t]), d), 1e-6) << t;
    }
}

TEST(VectorField, CylinderGivesTheAxialAndTheCircumferentialField) {
    const Surface s = build_surface(make_cylinder(40, 16, 1.0, 3.0));
    for (const FieldInterpolation &how : {heat, harmonic}) {
        // Axial control: every triangle points along the axis.
        TangentField f = vector_heat_field(
            s.crps, {control_at(s.crps, {1, 0.2, 0}, {0, 1, 0})}, 1, how);
        double worst = 0;
        for (TriId t = 0; t < s.crps.num_triangles(); ++t)
            worst =
                std::max(worst, angle_deg(field_to_world(s.crps, t, f.a[t]), {0, 1, 0}));
        EXPECT_LT(worst, 1e-6);
        // Circumferential control: every triangle points around the axis, one way.
        f = vector_heat_field(s.crps, {control_at(s.crps, {1, 0.2, 0}, {0, 0, 1})}, 1,
                              how);
        worst = 0;
        for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
            const Vec3d c = centroid(s.crps, t);
            worst = std::max(worst,
                             angle_deg(field_to_world(s.crps, t, f.a[t]),
                                       in_plane(s.crps, t, cross(Vec3d{0, -1, 0}, c))));
        }
        EXPECT_LT(worst, 1e-6);
    }
}

// Rodrigues' rotation of v about the unit axis k by the angle a.
Vec3d rotate(Vec3d v, Vec3d k, double a) {
    return v * std::cos(a) + cross(k, v) * std::sin(a) +
           k * (dot(k, v) * (1 - std::cos(a)));
}

TEST(VectorField, SphereFollowsParallelTransportAlongGreatCircles) {
    const Surface s = build_surface(make_icosphere(4));
    const Vec3d p0 = normalize(Vec3d{1, 0.3, -0.2});
    const Vec3d v0 = normalize(cross(p0, Vec3d{0, 1, 0}));
    const TangentControl k = control_at(s.crps, p0, v0);
    const TangentField f = vector_heat_field(s.crps, {k}, 1, heat);
    std::vector<double> err;
    for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
        const Vec3d p = normalize(centroid(s.crps, t));
        const double theta = std::acos(std::clamp(dot(p0, p), -1.0, 1.0));
        if (theta > 2.0 || theta < 1e-9) continue;  // away from the cut locus (antipode)
        const Vec3d expected = rotate(v0, normalize(cross(p0, p)), theta);
        const Vec3d got = field_to_world(s.crps, t, f.a[t]);
        EXPECT_LT(std::abs(dot(got, s.crps.frame(t).normal)), 1e-12);  // tangent
        err.push_back(angle_deg(got, expected));
    }
    std::sort(err.begin(), err.end());
    ASSERT_GT(err.size(), 3000u);
    EXPECT_LT(err[err.size() / 2], 1.0);
    EXPECT_LT(err[err.size() * 95 / 100], 2.0);
    EXPECT_LT(err.back(), 5.0);
}

TEST(VectorField, SmoothAcrossEdgesAndEqualToTheControlsAtTheirTriangles) {
    const Surface s = build_surface(make_icosphere(4));
    const std::vector<TangentControl> controls = {
        control_at(s.crps, {1, 0, 0}, {0, 1, 0}),
        control_at(s.crps, {0, 0, 1}, {1, 1, 0}),
        control_at(s.crps, {-0.6, 0.8, 0}, {0, 0, 1}),
    };
    const TangentField f = vector_heat_field(s.crps, controls, 1, harmonic);
    for (const TangentControl &k : controls) {
        const Vec3d n = s.crps.frame(k.tri).normal;
        const Vec3d d = normalize(k.direction - n * dot(k.direction, n));
        EXPECT_LT(angle_deg(field_to_world(s.crps, k.tri, f.a[k.tri]), d), 1e-9);
        // Its neighbours, from the flow alone, agree with it too.
        for (TriId j : s.crps.topology().primary_neighbours(k.tri)) {
            RigidMap2 to_k;
            ASSERT_TRUE(s.crps.find_map(k.tri, j, &to_k));
            const Vec2d aj{to_k.c * f.a[j].x - to_k.s * f.a[j].y,
                           to_k.s * f.a[j].x + to_k.c * f.a[j].y};
            EXPECT_LT(angle_deg(field_to_world(s.crps, k.tri, aj), d), 5.0);
        }
    }
    // Each vector carried across the shared edge into its neighbour's frame (the
    // unfolding's rotation, the discrete parallel transport across the edge).
    std::vector<double> turn;
    for (TriId i = 0; i < s.crps.num_triangles(); ++i) {
        const auto nbrs = s.crps.topology().primary_neighbours(i);
        const auto maps = s.crps.to_master(i);
        for (size_t q = 0; q < nbrs.size(); ++q) {
            const Vec2d a = f.a[nbrs[q]], b = f.a[i];
            const Vec2d carried{maps[q].c * a.x - maps[q].s * a.y,
                                maps[q].s * a.x + maps[q].c * a.y};
            turn.push_back(std::atan2(std::abs(cross(carried, b)), dot(carried, b)) *
                           deg);
        }
    }
    std::sort(turn.begin(), turn.end());
    // Edges of this sphere subtend about 3°. A tangent field on a sphere has
    // singularities (index sum 2), where it turns fast: the last few percent.
    EXPECT_LT(turn[turn.size() / 2], 1.5);
    EXPECT_LT(turn[turn.size() * 95 / 100], 8.0);
}

TEST(VectorField, APieceWithoutAControlGetsNoField) {
    // Two spheres side by side; the control is on the first.
    TriangleMesh m = make_icosphere(2);
    const TriangleMesh other = make_icosphere(2);
    const VertId offset = VertId(m.positions.size());
    for (const Vec3d &p : other.positions) m.positions.push_back(p + Vec3d{3, 0, 0});
    for (auto tri : other.triangles)
        m.triangles.push_back({tri[0] + offset, tri[1] + offset, tri[2] + offset});
    const Surface s = build_surface(m);
    for (const FieldInterpolation &how : {heat, harmonic}) {
        const TangentField f =
            vector_heat_field(s.crps, {control_at(s.crps, {1, 0, 0}, {0, 1, 0})}, 1, how);
        size_t with = 0, without = 0;
        for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
            const bool first = centroid(s.crps, t).x < 1.5;
            if (first) with += length(f.a[t]) > 0;
            if (!first) without += length(f.a[t]) == 0;
        }
        EXPECT_EQ(with, other.triangles.size());
        EXPECT_EQ(without, other.triangles.size());
    }
}

TEST(VectorField, IndependentOfTheThreadCount) {
    const Surface s = build_surface(make_icosphere(3));
    const FieldSpec spec = parse_field_spec(
        nlohmann::json::parse(
            R"({"controls": [{"at": [1, 0.5, 0.5], "direction": [0, 1, 0]},
                             {"at": [0.5, 0.5, 0], "direction": [1, 0, 0]}]})"),
        "f", "test");
    TangentField one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = resolve_field(spec, s.crps, 1);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = resolve_field(spec, s.crps, 1);
    }
    ASSERT_EQ(one.a.size(), two.a.size());
    for (size_t t = 0; t < one.a.size(); ++t) ASSERT_EQ(one.a[t], two.a[t]) << t;
}

TEST(FieldSpec, AlongAndAroundTheBodyAxis) {
    // A cylinder three times as long as it is wide: its principal axis is Y.
    const Surface s = build_surface(make_cylinder(40, 30, 1.0, 6.0));
    const auto spec = [](const char *text) {
        return parse_field_spec(nlohmann::json::parse(text), "f", "test");
    };
    const TangentField along =
        resolve_field(spec(R"({"along": "body_axis"})"), s.crps, 0.5);
    const TangentField around =
        resolve_field(spec(R"({"around": "body_axis"})"), s.crps, 0.5);
    for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
        const Vec3d c = centroid(s.crps, t);
        EXPECT_NEAR(length(along.a[t]), 0.5, 1e-12);
        EXPECT_LT(axis_angle_deg(field_to_world(s.crps, t, along.a[t]), {0, 1, 0}), 1e-6);
        EXPECT_LT(axis_angle_deg(field_to_world(s.crps, t, around.a[t]),
                                 in_plane(s.crps, t, cross(Vec3d{0, 1, 0}, c))),
                  1e-6);
    }
}

TEST(FieldSpec, BoxSpacePointsAreFractionsOfTheBoundingBox) {
    const Surface s = build_surface(make_plane(10, 10, 4.0, 2.0));  // x ∈ [-2, 2]
    const FieldSpec spec = parse_field_spec(
        nlohmann::json::parse(
            R"({"controls": [{"at": [0.75, 0.5, 0.5], "direction": [1, 5, 0]}]})"),
        "f", "test");
    EXPECT_TRUE(spec.box_space);
    const TangentField f = resolve_field(spec, s.crps, 1);
    const NearestPoint q = nearest_surface_point(s.crps, {1.0, 0, 0});
    EXPECT_LT(angle_deg(field_to_world(s.crps, q.tri, f.a[q.tri]), {1, 0, 0}), 1e-6);
}

TEST(FieldSpec, ErrorsNameTheJsonPath) {
    const auto error_of = [](const char *text) -> std::string {
        try {
            parse_field_spec(nlohmann::json::parse(text), "simulation.anisotropy.field",
                             "p.json");
        } catch (const InputError &e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(
        error_of(R"({"around": "spine"})"),
        "p.json: simulation.anisotropy.field.around: 'spine': expected \"body_axis\"");
    EXPECT_EQ(error_of(R"({"around": "body_axis", "along": "body_axis"})"),
              "p.json: simulation.anisotropy.field: give exactly one of \"direction\", "
              "\"along\", \"around\" or \"controls\"");
    EXPECT_EQ(
        error_of(R"({"controls": [{"at": [0, 0, 0], "direction": [0, 0, 0]}]})"),
        "p.json: simulation.anisotropy.field.controls[0].direction: must not be the "
        "zero vector");
    EXPECT_EQ(error_of(R"({"controls": [{"at": [0, 0], "direction": [0, 0, 1]}]})"),
              "p.json: simulation.anisotropy.field.controls[0].at: expected 3 numbers");
    EXPECT_EQ(error_of(R"({"controls": [{"direction": [0, 0, 1]}]})"),
              "p.json: simulation.anisotropy.field.controls[0].at: missing");
    EXPECT_EQ(error_of(R"({"controls": [], "space": "box"})"),
              "p.json: simulation.anisotropy.field.controls: expected an array of 1 to "
              "10000 {\"at\", \"direction\"}");
    EXPECT_EQ(
        error_of(
            R"({"controls": [{"at": [0, 0, 0], "direction": [0, 0, 1]}], "space": "uv"})"),
        "p.json: simulation.anisotropy.field.space: 'uv': expected \"box\" or \"world\"");
    EXPECT_EQ(error_of(R"({"direction": [0, 1, 0], "space": "box"})"),
              "p.json: simulation.anisotropy.field.space: only with \"controls\"");
    EXPECT_EQ(error_of(R"({"direction": [0, 1, 0], "colour": 1})"),
              "p.json: simulation.anisotropy.field.colour: unknown key");
    EXPECT_EQ(error_of(R"([1])"),
              "p.json: simulation.anisotropy.field: expected an object");
}

TEST(FieldSpec, AControlNormalToTheSurfaceIsAnError) {
    const Surface s = build_surface(make_plane(4, 4, 1.0, 1.0));
    const FieldSpec spec = parse_field_spec(
        nlohmann::json::parse(
            R"({"controls": [{"at": [0, 0, 0], "direction": [0, 1, 0]}], "space": "world"})"),
        "f", "test");
    EXPECT_THROW(resolve_field(spec, s.crps, 1), InputError);
}

}  // namespace
}  // namespace pelage::sim
