// Moving a cell across the surface: the cell-in-triangle walk of Teo 2006 §5.2. A 2D
// displacement in the cell's triangle frame is followed edge by edge: where the segment
// leaves the triangle, the rest of the displacement is carried into the triangle across
// that edge by the CRPS edge map F[t→n] (Teo §4.3), until it ends inside a triangle.
// Boundary (and non-manifold) edges stop the cell on the edge: a cell never leaves the
// surface. Tests of "inside" are orientation-agnostic (CCW faces have negative 2D area).
#pragma once

#include "sim/crps/crps.h"

namespace pelage::sim {

struct SurfacePoint {
    TriId tri = 0;
    Vec2d p;  // in tri's local 2D frame
};

// Smallest barycentric coordinate of p in the reference triangle (≥ 0 inside).
double min_barycentric(const CrpsFrame &f, Vec2d p);
// p moved to the closest point of the triangle when it lies outside (clamped
// barycentrics), else p unchanged.
Vec2d clamp_into_triangle(const CrpsFrame &f, Vec2d p);

// Follows displacement d (in start.tri's frame) across the surface. The result is inside
// its triangle (min_barycentric ≥ 0 up to rounding, and clamped when not).
SurfacePoint walk(const Crps &crps, SurfacePoint start, Vec2d d);

}  // namespace pelage::sim
