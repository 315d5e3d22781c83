// The closest point of a triangle, and of a whole mesh, to a point in space: the one
// implementation the landmark regions (sim/control), the growth's rest-shape points
// (sim/growth) and the rendering of a pattern on another mesh (pattern/transfer) use.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct TrianglePoint {
    Vec3d point;  // the closest point itself
    Vec3d bary;   // its barycentric coordinates (weights of a, b, c)
};

// The closest point of triangle abc to p by Voronoi regions of the vertices, edges and
// face (C. Ericson, Real-Time Collision Detection, 2005, §5.1.5). Inline: callers that
// need only one of the two results let the compiler drop the other.
inline TrianglePoint closest_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}};  // vertex region a
    const Vec3d bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}};  // vertex region b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge ab
        const double v = d1 / (d1 - d3);
        return {a + ab * v, {1 - v, v, 0}};
    }
    const Vec3d cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}};  // vertex region c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge ac
        const double w = d2 / (d2 - d6);
        return {a + ac * w, {1 - w, 0, w}};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge bc
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {b + (c - b) * w, {0, 1 - w, w}};
    }
    const double denom = 1 / (va + vb + vc);  // inside the face
    const double v = vb * denom, w = vc * denom;
    return {a + ab * v + ac * w, {1 - v - w, v, w}};
}

inline Vec3d closest_point_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
    return closest_on_triangle(p, a, b, c).point;
}

// The distance from p to triangle t in the plane, 0 inside (either orientation): the
// one 2D point-triangle distance, for the unfoldings' pruning (sim/crps), the
// closest-cell index (pattern/mosaic) and the atlas's chart masks (pattern/bake).
double point_triangle_distance(Vec2d p, const Vec2d t[3]);

// The closest point of a mesh to a point in space: the one result type of every search
// below.
struct MeshPoint {
    TriId tri = 0;
    Vec3d point;  // the closest point itself
    Vec3d bary;   // its barycentric coordinates in `tri`
    double distance = std::numeric_limits<double>::infinity();  // from the query point
};

// The closest point of a mesh by testing every triangle, for a few points (the
// landmarks of a "near" region); the lowest-numbered triangle among the closest ones
// (deterministic).
MeshPoint closest_surface_point(const TriangleMesh &mesh, Vec3d p);

// What a search ranks the triangles by. Where two triangles are equally close (a point
// outside a convex edge projects onto the edge in both), the two rankings may pick
// different triangles by rounding, so each caller keeps the one its results were made
// with: the landmark regions' transfer (sim/control) and the rendering on another mesh
// (pattern/transfer) rank by the closest point, the growth's rest-shape points
// (sim/growth) by the point their barycentrics blend from the corners.
enum class RankBy {
    point,              // length(closest point - p)
    barycentric_blend,  // length_squared(corners blended by the barycentrics - p)
};

// The triangles of a mesh in a uniform grid of cubes about the mean edge length (hashed,
// so an elongated mesh costs only its occupied cells), searched shell by shell outwards
// until no closer triangle can remain. The mesh must outlive the grid.
class ClosestPointGrid {
  public:
    explicit ClosestPointGrid(const TriangleMesh &mesh);

    // The closest point of the mesh to p; ties go to the lowest triangle id, so the
    // answer does not depend on the order cells are visited in. An empty mesh gives
    // tri = invalid_id.
    MeshPoint closest(Vec3d p, RankBy rank = RankBy::point) const;
    // Ranked by point; among triangles equally close (within `tie`: where sheets of the
    // surface touch or cross) the one whose plane faces most like `normal` wins.
    MeshPoint closest_facing(Vec3d p, Vec3d normal, double tie) const;

  private:
    template <typename Visit>
    void search(Vec3d p, const double &reach, Visit &&visit) const;
    std::array<int, 3> index_of(Vec3d p) const;
    static uint64_t key(int i, int j, int k);

    const TriangleMesh *m_mesh;
    Vec3d m_lo;
    double m_cell = 1;
    int m_n[3] = {1, 1, 1};
    std::unordered_map<uint64_t, std::vector<TriId>> m_cells;
};

// The closest point of `mesh` to each of `points` (ClosestPointGrid::closest).
std::vector<MeshPoint> closest_points(const TriangleMesh &mesh,
                                      const std::vector<Vec3d> &points,
                                      RankBy rank = RankBy::point);

}  // namespace pelage::sim
