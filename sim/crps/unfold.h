// Breadth-first unfolding of the surface around a master triangle (Teo 2006 §4.1,
// Fig. 4.2): every triangle within a radius, with the composed rigid map that carries
// it into the master's reference plane. This is the neighbourhood used by relaxation
// (sim) and by the closest-cell search (shader).
//
// The walk crosses primary and secondary neighbours; each accepted triangle's map is
// its parent's map composed with the stored F[j→parent], and the first path that reaches
// a triangle within the radius wins (fewest hops, then lowest parent order): the result
// is deterministic.
#pragma once

#include <vector>

#include "sim/crps/crps.h"

namespace pelage::sim {

struct UnfoldedTriangle {
    TriId tri;
    uint32_t depth;       // hops from the master (0 for the master itself)
    RigidMap2 to_master;  // F[tri→master]
    // A lower bound on the 2D distance from the query region to the mapped triangle:
    // exact when the triangle is near the radius, possibly less for triangles well
    // inside.
    double distance;
};

// Reusable per-thread state: a visit stamp per triangle, so repeated unfoldings cost
// nothing to reset.
class UnfoldScratch {
  public:
    void prepare(size_t num_triangles);
    bool visit(TriId t) {  // true the first time t is seen in this unfolding
        if (m_stamp[t] == m_generation) return false;
        m_stamp[t] = m_generation;
        return true;
    }
    void unvisit(TriId t) { m_stamp[t] = m_generation - 1; }
    void begin();

  private:
    std::vector<uint32_t> m_stamp;
    uint32_t m_generation = 0;
};

// Which neighbour maps the walk may compose. Teo's neighbourhood uses both; walking
// across edges only makes the unfoldings of two edge-adjacent triangles agree on every
// triangle reached through their shared edge (F[i→j] is exactly F[j→i]^-1). That cuts
// the closest-cell search's edge disagreements ("cracks", Teo §6.3) to about a third
// (`pelage bench lookup` measures both).
enum class UnfoldPaths { edges_and_vertices, edges_only };

// Triangles whose mapped reference triangle lies within `radius` of the master triangle.
void unfold_around_triangle(const Crps &crps, TriId master, double radius,
                            std::vector<UnfoldedTriangle> &out, UnfoldScratch &scratch,
                            UnfoldPaths paths = UnfoldPaths::edges_and_vertices);

// Triangles whose mapped reference triangle lies within `radius` of point q (master's
// local 2D coordinates).
void unfold_around_point(const Crps &crps, TriId master, Vec2d q, double radius,
                         std::vector<UnfoldedTriangle> &out, UnfoldScratch &scratch,
                         UnfoldPaths paths = UnfoldPaths::edges_and_vertices);

// --- 2D distance helpers (exposed for tests and for the shader's pruning) ---
// point_triangle_distance is in sim/mesh/closest_point.h.
double triangle_triangle_distance(const Vec2d a[3], const Vec2d b[3]);

}  // namespace pelage::sim
