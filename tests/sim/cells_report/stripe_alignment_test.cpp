// The stripe alignment measure (sim/cells_report/stripe_alignment.h) on synthetic stripes
// of known direction: straight stripes on a plane against fields at known angles, and
// latitude bands on a sphere against the circles about its axis and the meridians.
#include "sim/cells_report/stripe_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/crps/surface.h"
#include "sim/field/field_spec.h"
#include "sim/field/vector_heat.h"
#include "sim/mesh/procedural_mesh.h"
#include "sim/run/cells_data.h"

namespace pelage::sim {
namespace {

constexpr double pi = 3.14159265358979323846;

CellTypes two_types() {
    CellType f, b;
    f.name = "F";
    b.name = "B";
    return CellTypes({f, b}, {{1, 0}, {0, 1}}, {{0, 0}, {0, 0}});
}

// Cells at the points, F where `is_f`, each on its nearest triangle.
template <typename IsF>
CellsData cells_at(const Surface &s, const std::vector<Vec3d> &points, IsF is_f) {
    Cells cells(s.crps.num_triangles());
    for (const Vec3d &p : points) {
        const NearestPoint q = nearest_surface_point(s.crps, p);
        cells.add({q.tri, s.crps.barycentric_to_2d(q.tri, q.barycentric)},
                  is_f(p) ? 0 : 1);
    }
    return make_cells_data(s.mesh, s.crps, two_types(), cells, "{}", 1);
}

// A hexagonal lattice with a little jitter: cells as a relaxed mosaic packs them.
std::vector<Vec3d> plane_points(double half, double spacing) {
    std::vector<Vec3d> out;
    uint32_t h = 12345;
    auto jitter = [&] {
        h = h * 1664525u + 1013904223u;
        return (double(h >> 8) / double(1u << 24) - 0.5) * 0.2 * spacing;
    };
    const double dz = spacing * std::sqrt(3.0) / 2;
    int row = 0;
    for (double z = -half; z <= half; z += dz, ++row)
        for (double x = -half + (row % 2) * spacing / 2; x <= half; x += spacing)
            out.push_back({x + jitter(), 0, z + jitter()});
    return out;
}

TEST(StripeAlignment, StraightStripesAgainstFieldsAtKnownAngles) {
    const Surface s = build_surface(make_plane(24, 24, 2.0, 2.0));
    const std::vector<Vec3d> points = plane_points(0.99, 0.02);
    for (double stripe_deg : {0.0, 35.0, 100.0}) {
        // Stripes along (cos θ, sin θ) in (x, z), 0.12 wide (about six cells).
        const double th = stripe_deg * pi / 180;
        const Vec3d normal{-std::sin(th), 0, std::cos(th)};
        const CellsData d = cells_at(s, points, [&](Vec3d p) {
            return std::sin(2 * pi * dot(p, normal) / 0.24) > 0;
        });
        for (double field_deg : {0.0, 20.0, 45.0, 70.0, 90.0}) {
            const double ph = (stripe_deg + field_deg) * pi / 180;
            const TangentField f =
                constant_world_field(s.crps, {std::cos(ph), 0, std::sin(ph)}, 1);
            const StripeAlignment a = measure_stripe_alignment(d, s.crps, f);
            ASSERT_GT(a.samples, 1000u);
            EXPECT_NEAR(a.median, field_deg, 3.0) << stripe_deg << " " << field_deg;
            EXPECT_LT(a.q3 - a.q1, 12.0) << stripe_deg << " " << field_deg;
            EXPECT_GT(a.coherence, 0.2);
        }
    }
}

TEST(StripeAlignment, LatitudeBandsFollowCirclesAboutTheAxis) {
    const Surface s = build_surface(make_icosphere(4));
    // Fibonacci points, about uniform on the sphere, jittered by a third of their
    // spacing: a lattice's rows would alias the bands into staircases where a band
    // crosses them at a small angle, which a relaxed mosaic does not have.
    std::vector<Vec3d> points;
    const int n = 24000;
    const double spacing = std::sqrt(4 * pi / n);
    uint32_t h = 777;
    auto jitter = [&] {
        h = h * 1664525u + 1013904223u;
        return (double(h >> 8) / double(1u << 24) - 0.5) * 0.66 * spacing;
    };
    for (int i = 0; i < n; ++i) {
        const double y = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - y * y);
        const double phi = i * pi * (3 - std::sqrt(5.0));
        const Vec3d p{r * std::cos(phi), y, r * std::sin(phi)};
        points.push_back(normalize(p + Vec3d{jitter(), jitter(), jitter()}));
    }
    // Bands of latitude up to 53° (nearer the poles the circles curve more within the
    // measure's window than its resolution).
    const CellsData d = cells_at(s, points, [](Vec3d p) {
        return std::abs(p.y) < 0.8 && std::sin(9 * std::asin(p.y)) > 0;
    });
    TangentField around, meridian;
    for (TriId t = 0; t < s.crps.num_triangles(); ++t) {
        const Vec3d c = s.crps.to_3d(t, {0, 0});
        const Vec3d e = cross(Vec3d{0, 1, 0}, c);
        around.a.push_back(world_to_field(s.crps, t, e));
        meridian.a.push_back(world_to_field(s.crps, t, cross(c, e)));
    }
    const StripeAlignment a = measure_stripe_alignment(d, s.crps, around);
    const StripeAlignment m = measure_stripe_alignment(d, s.crps, meridian);
    ASSERT_GT(a.samples, 3000u);
    EXPECT_LT(a.median, 6.0);  // 4.9° measured
    EXPECT_LT(a.q3, 10.0);
    EXPECT_GT(m.median, 80.0);
    EXPECT_GT(m.q1, 75.0);
}

TEST(StripeAlignment, RoundSpotsHaveNoDirection) {
    const Surface s = build_surface(make_plane(24, 24, 2.0, 2.0));
    // Round spots on a square grid: boundaries turn every way.
    const CellsData d = cells_at(s, plane_points(0.99, 0.02), [](Vec3d p) {
        const double u = std::remainder(p.x, 0.15), v = std::remainder(p.z, 0.15);
        return u * u + v * v < 0.035 * 0.035;
    });
    const TangentField f = constant_world_field(s.crps, {1, 0, 0}, 1);
    const StripeAlignment a = measure_stripe_alignment(d, s.crps, f);
    ASSERT_GT(a.samples, 500u);
    EXPECT_NEAR(a.median, 45.0, 10.0);  // uniform in [0°, 90°]
    EXPECT_LT(a.coherence, 0.2);
}

}  // namespace
}  // namespace pelage::sim
