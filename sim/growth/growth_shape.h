// A growth spec (growth_spec.h) resolved on the vertices of the surface a simulation
// runs on: one position per vertex and key, interpolated at any age.
//
// The rest mesh is the mesh a pattern is written on (`pelage sim --mesh`); keys give the
// shape at their ages. The simulation may run on a simplified copy of it
// (sim/remesh/cell_scale_surface.h), whose vertices lie within a small distance of the
// rest mesh but are not its vertices:
//   * scale and cylinder keys are functions of the position, applied to the copy's
//     vertices directly;
//   * a mesh key moves each of the copy's vertices by the displacement of its closest
//     point on the rest mesh (barycentric in the rest triangle), so a key equal to the
//     rest mesh leaves the copy exactly in place.
#pragma once

#include <vector>

#include "sim/growth/growth_spec.h"
#include "sim/mesh/mesh.h"

namespace pelage::sim {

class GrowthShape {
  public:
    GrowthShape() = default;
    // positions[k] holds every vertex at ages[k]; ages strictly increase.
    GrowthShape(std::vector<double> ages, std::vector<std::vector<Vec3d>> positions,
                GrowthInterpolation interpolation, double interval);

    bool empty() const { return m_ages.empty(); }
    size_t num_vertices() const { return m_keys.empty() ? 0 : m_keys[0].size(); }
    double interval() const { return m_interval; }
    double first_age() const { return m_ages.front(); }
    double last_age() const { return m_ages.back(); }
    // The shape at `age`: the first key before the first age, the last after the last;
    // between keys i and i+1 at s = (age − t_i) / (t_{i+1} − t_i) ∈ [0, 1]:
    //   linear  (1 − s)·P_i + s·P_{i+1}
    //   smooth  the cubic Hermite spline with Catmull–Rom tangents for uneven ages,
    //           m_i = (P_{i+1} − P_{i−1}) / (t_{i+1} − t_{i−1}) (one-sided at the ends):
    //           it passes through every key with a continuous velocity (growth has no
    //           kink at a key); with two keys it is the straight line.
    std::vector<Vec3d> at(double age) const;

  private:
    std::vector<double> m_ages;
    std::vector<std::vector<Vec3d>> m_keys;
    GrowthInterpolation m_interpolation = GrowthInterpolation::linear;
    double m_interval = 1;
};

// Walter thesis §5.5–5.6, §4.4 (L1350–1362): the point p of the rest pose grown by the
// cylinders with per-cylinder (length, radius) scales. Each cylinder alone scales the
// point's axial coordinate by L and its radial offset by R about its pivot, the pivot
// itself moved by the parent's growth (scales are absolute, only the pivot's
// translation is inherited). A point inside several cylinders takes their results
// weighted by 1 − d (d the distance to the axis over the radius), normalised; a point
// inside none stays where it is ("a point in space is transformed only if it is inside
// at least one cylinder").
Vec3d grow_by_cylinders(const std::vector<GrowthCylinder> &cylinders,
                        const std::vector<std::array<double, 2>> &scales, Vec3d p);

// How many vertices of `mesh` lie inside none of the cylinders (they do not move under a
// cylinder key): 0 when the cylinders enclose the body, as they should.
size_t vertices_outside_cylinders(const std::vector<GrowthCylinder> &cylinders,
                                  const TriangleMesh &mesh);

// Area-weighted centroid of the surface: the fixed point of a uniform scale key.
Vec3d area_centroid(const TriangleMesh &mesh);

// Every vertex of `rest` in key `k`'s shape. A mesh key is loaded and checked against
// the rest topology: InputError naming the preset and key when it differs.
std::vector<Vec3d> key_positions(const GrowthSpec &spec, size_t k,
                                 const TriangleMesh &rest);

// The spec on the vertices of `surface`: `rest` itself (same vertices and triangles) or
// a copy close to it (see the file comment).
GrowthShape resolve_growth(const GrowthSpec &spec, const TriangleMesh &rest,
                           const TriangleMesh &surface);

}  // namespace pelage::sim
