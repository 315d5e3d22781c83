// The Canonical Reference Plane Structure of H. J. Teo, "Pattern Formation and Mapping
// for Animal Skin Synthesis", M.Eng thesis, NTU 2006, ch. 4.
//
// Every triangle t is rotated by R_t so its (consistently oriented) normal points to +Y;
// dropping Y gives its *reference triangle* in 2D (Teo §4.2, Fig. 4.4). pelage keeps each
// reference triangle's coordinates relative to its own centroid, so 2D values stay the
// size of a triangle (precise even in float) and:
//     p_2d = (R_t p).xz - centre_t,     p = R_t^T (p_2d.x + centre.x, y_offset, p_2d.y +
//     centre.y).
// A point on the surface is (t, p_2d). Note: with normal +Y, (x, z) is a left-handed
// pair, so counter-clockwise faces have negative signed area in 2D; nothing here depends
// on it.
//
// For every (triangle i, neighbour j) pair of the topology, the rigid map F[j→i] takes
// j's reference plane into i's (Teo §4.3, Fig. 4.7), stored with its inverse F[i→j]:
//   * edge neighbours unfold about the shared edge (its endpoints coincide after
//   mapping);
//   * vertex neighbours rotate about the line where the two planes meet, through the
//     shared vertex (Teo §4.1, Fig. 4.2); coplanar or folded-flat planes align in-plane.
// Thread-safety: immutable after build; all queries are const.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "sim/core/check.h"
#include "sim/crps/rigid_map.h"
#include "sim/mesh/mesh.h"
#include "sim/mesh/topology.h"

namespace pelage::sim {

struct CrpsFrame {           // Teo §4.2, Table 1 (Normal, Yoffset, Center, vertices)
    Mat3d rotation;          // R_t: world -> canonical, normal -> +Y
    Vec3d normal;            // unit normal, consistently oriented (Topology::flipped)
    double y_offset = 0;     // (R_t p).y for every p on the triangle's plane
    Vec2d centre;            // (R_t centroid).xz: where local 2D coordinates start
    std::array<Vec2d, 3> v;  // the reference triangle, local 2D coordinates
    double area = 0;
    double bound_radius =
        0;  // max |v[c]|: a circle about the centroid holding the triangle
};

// Barycentric coordinates (of corners 0, 1, 2) of local point p in a reference triangle.
Vec3d barycentric_in(const CrpsFrame &f, Vec2d p);

class Crps {
  public:
    // Takes the topology over (it is part of the structure: the maps follow its CSR).
    Crps(const TriangleMesh &mesh, Topology topo);

    size_t num_triangles() const { return m_frames.size(); }
    const CrpsFrame &frame(TriId t) const {
        PELAGE_DCHECK(t < m_frames.size());
        return m_frames[t];
    }
    const Topology &topology() const { return m_topo; }
    // The mesh vertices at t's corners (corner c of the reference triangle is v[c]).
    const std::array<VertId, 3> &corners(TriId t) const {
        PELAGE_DCHECK(t < m_triangles.size());
        return m_triangles[t];
    }

    // --- Conversions (exact up to rounding) ---
    Vec2d to_2d(TriId t, Vec3d p_world) const;  // projects onto t's plane
    Vec3d to_3d(TriId t, Vec2d p_2d) const;
    Vec2d barycentric_to_2d(TriId t, Vec3d b) const;
    Vec3d to_barycentric(TriId t, Vec2d p_2d) const;

    // --- Neighbour maps, parallel to topology().neighbours(i) ---
    // to_master(i)[k] = F[j→i] and to_neighbour(i)[k] = F[i→j] for j = neighbours(i)[k].
    std::span<const RigidMap2> to_master(TriId i) const {
        PELAGE_DCHECK(size_t(i) + 1 < m_topo.nbr_row.size());
        return {m_to_master.data() + m_topo.nbr_row[i],
                m_topo.nbr_row[i + 1] - m_topo.nbr_row[i]};
    }
    std::span<const RigidMap2> to_neighbour(TriId i) const {
        PELAGE_DCHECK(size_t(i) + 1 < m_topo.nbr_row.size());
        return {m_to_nbr.data() + m_topo.nbr_row[i],
                m_topo.nbr_row[i + 1] - m_topo.nbr_row[i]};
    }
    // F[j→i] for any neighbour j of i; false when j is not a neighbour.
    bool find_map(TriId i, TriId j, RigidMap2 *j_to_i) const;

  private:
    RigidMap2 edge_map(TriId i, TriId j, VertId a, VertId b) const;
    RigidMap2 vertex_map(TriId i, TriId j, VertId v) const;
    Vec2d vertex_2d(TriId t, VertId v) const;  // reference position of mesh vertex v in t

    Topology m_topo;
    std::vector<std::array<VertId, 3>> m_triangles;  // vertex ids, for vertex_2d
    std::vector<CrpsFrame> m_frames;
    std::vector<RigidMap2> m_to_master, m_to_nbr;
};

}  // namespace pelage::sim
