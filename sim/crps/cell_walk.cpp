#include "sim/crps/cell_walk.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {

namespace {

// Barycentric coordinates of p with respect to the reference triangle.
void barycentric(const CrpsFrame &f, Vec2d p, double b[3]) {
    const Vec2d e1 = f.v[1] - f.v[0], e2 = f.v[2] - f.v[0], q = p - f.v[0];
    const double det = cross(e1, e2);
    b[1] = cross(q, e2) / det;
    b[2] = cross(e1, q) / det;
    b[0] = 1.0 - b[1] - b[2];
}

// A few crossings per step are normal; this cap only guards against a cycle of
// rounding errors on degenerate geometry.
constexpr int max_crossings = 256;

}  // namespace

double min_barycentric(const CrpsFrame &f, Vec2d p) {
    double b[3];
    barycentric(f, p, b);
    return std::min({b[0], b[1], b[2]});
}

Vec2d clamp_into_triangle(const CrpsFrame &f, Vec2d p) {
    double b[3];
    barycentric(f, p, b);
    if (b[0] >= 0 && b[1] >= 0 && b[2] >= 0) return p;
    // Closest point on the triangle: the closest point over the three edges.
    Vec2d best = f.v[0];
    double best_d2 = 1e300;
    for (int k = 0; k < 3; ++k) {
        const Vec2d a = f.v[k], e = f.v[(k + 1) % 3] - a;
        const double len2 = length_squared(e);
        const double s = len2 > 0 ? std::clamp(dot(p - a, e) / len2, 0.0, 1.0) : 0.0;
        const Vec2d c = a + e * s;
        const double d2 = length_squared(p - c);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = c;
        }
    }
    return best;
}

SurfacePoint walk(const Crps &crps, SurfacePoint cur, Vec2d d) {
    const Topology &topo = crps.topology();
    TriId came_from = invalid_id;
    for (int crossing = 0; crossing < max_crossings; ++crossing) {
        const CrpsFrame &f = crps.frame(cur.tri);
        // Orientation sign: inside means sigma·cross(edge, p − v_k) ≥ 0 for all edges.
        const double sigma = cross(f.v[1] - f.v[0], f.v[2] - f.v[0]) > 0 ? 1.0 : -1.0;
        // --- Find where the segment cur.p + s·d (s in [0, 1]) first leaves the triangle
        // ---
        double s_exit = 1.0;
        int k_exit = -1;
        for (int k = 0; k < 3; ++k) {
            const Vec2d e = f.v[(k + 1) % 3] - f.v[k];
            const double g =
                sigma * cross(e, d);  // rate of change of the inside function
            if (g >= 0) continue;     // moving away from (or along) edge k
            const double h = sigma * cross(e, cur.p - f.v[k]);
            const double s = std::max(0.0, -h / g);
            if (s < s_exit) {
                s_exit = s;
                k_exit = k;
            }
        }
        if (k_exit < 0) {  // ends inside
            cur.p = clamp_into_triangle(f, cur.p + d);
            return cur;
        }
        const Vec2d exit = cur.p + d * s_exit;
        const TriId n = topo.across(cur.tri, k_exit);
        RigidMap2 F;  // F[t→n]
        if (n == invalid_id || (n == came_from && s_exit == 0.0) ||
            !crps.find_map(n, cur.tri, &F)) {
            // Boundary edge (or a rounding ping-pong): the cell stops on the edge.
            cur.p = clamp_into_triangle(f, exit);
            return cur;
        }
        d = F.apply_direction(d * (1.0 - s_exit));
        came_from = cur.tri;
        cur = {n, F.apply(exit)};
    }
    cur.p = clamp_into_triangle(crps.frame(cur.tri), cur.p);
    return cur;
}

}  // namespace pelage::sim
