// Implements the CRPS of H. J. Teo, M.Eng thesis, NTU 2006, ch. 4 (see crps.h).
#include "sim/crps/crps.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace pelage::sim {
namespace {

// The minimal rotation taking unit vector n to +Y (Rodrigues: R = I + [v]x +
// [v]x^2/(1+c), v = n x Y, c = n.Y). For normals in the lower hemisphere we first turn by
// π about X, so 1 + c never approaches 0.
Mat3d rotation_to_y(Vec3d n) {
    Mat3d flip;  // identity
    if (n.y < 0) {
        flip.m[1][1] = -1;
        flip.m[2][2] = -1;
        n = {n.x, -n.y, -n.z};
    }
    const Vec3d v{-n.z, 0, n.x};  // n × (0, 1, 0)
    const double k = 1.0 / (1.0 + n.y);
    const double vx[3][3] = {{0, -v.z, v.y}, {v.z, 0, -v.x}, {-v.y, v.x, 0}};
    Mat3d r;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            double vx2 = 0;
            for (int c = 0; c < 3; ++c) vx2 += vx[a][c] * vx[c][b];
            r.m[a][b] = (a == b ? 1.0 : 0.0) + vx[a][b] + vx2 * k;
        }
    Mat3d out;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            double sum = 0;
            for (int c = 0; c < 3; ++c) sum += r.m[a][c] * flip.m[c][b];
            out.m[a][b] = sum;
        }
    return out;
}

Vec2d xz(Vec3d p) { return {p.x, p.z}; }

}  // namespace

Crps::Crps(const TriangleMesh &mesh, Topology topo)
    : m_topo(std::move(topo)), m_triangles(mesh.triangles) {
    const size_t nt = mesh.num_triangles();
    // The topology must be the mesh's own (build_topology(mesh)): the maps index its CSR.
    PELAGE_CHECK(m_topo.nbr_row.size() == nt + 1 && m_topo.flipped.size() == nt);
    m_frames.resize(nt);

    // --- Reference triangles (Teo §4.2): rotate the normal to +Y, drop Y ---
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 1024), [&](const auto &range) {
        for (size_t t = range.begin(); t != range.end(); ++t) {
            CrpsFrame &f = m_frames[t];
            const Vec3d n_raw = mesh.face_normal_unnormalized(static_cast<TriId>(t));
            f.area = 0.5 * length(n_raw);
            f.normal = normalize(m_topo.flipped[t] ? -n_raw : n_raw);
            f.rotation = rotation_to_y(f.normal);
            const Vec3d p[3] = {mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2)};
            const Vec3d q[3] = {f.rotation * p[0], f.rotation * p[1], f.rotation * p[2]};
            const Vec3d qc = (q[0] + q[1] + q[2]) / 3.0;
            f.y_offset = qc.y;
            f.centre = xz(qc);
            for (int c = 0; c < 3; ++c) {
                f.v[c] = xz(q[c]) - f.centre;
                f.bound_radius = std::max(f.bound_radius, length(f.v[c]));
            }
        }
    });

    // --- Neighbour maps (Teo §4.3): F[j→i] and its inverse per CSR entry ---
    m_to_master.resize(m_topo.nbr.size());
    m_to_nbr.resize(m_topo.nbr.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 512), [&](const auto &range) {
        for (size_t ti = range.begin(); ti != range.end(); ++ti) {
            const TriId i = static_cast<TriId>(ti);
            const auto &tri_i = m_triangles[i];
            for (uint32_t k = m_topo.nbr_row[i]; k < m_topo.nbr_row[i + 1]; ++k) {
                const TriId j = m_topo.nbr[k];
                const auto &tri_j = m_triangles[j];
                VertId shared[3];
                int n_shared = 0;
                for (VertId a : tri_i)
                    if (std::find(tri_j.begin(), tri_j.end(), a) != tri_j.end())
                        shared[n_shared++] = a;
                // Two shared vertices: edge neighbour (also when it is a secondary entry
                // past the 255 primary cap). A duplicated face shares all three: unfold
                // about its first edge.
                const RigidMap2 F = n_shared >= 2 ? edge_map(i, j, shared[0], shared[1])
                                                  : vertex_map(i, j, shared[0]);
                m_to_master[k] = F;
                m_to_nbr[k] = F.inverse();
            }
        }
    });
}

Vec2d Crps::vertex_2d(TriId t, VertId v) const {
    const auto &tri = m_triangles[t];
    const int c = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
    return m_frames[t].v[c];
}

// Teo §4.3, Fig. 4.6: rotate j about Y so the shared edge is parallel to i's copy of it,
// then translate it onto i's copy (we align the edge midpoints, which halves the rounding
// error at the endpoints compared with aligning one endpoint).
RigidMap2 Crps::edge_map(TriId i, TriId j, VertId a, VertId b) const {
    const Vec2d a_i = vertex_2d(i, a), b_i = vertex_2d(i, b);
    const Vec2d a_j = vertex_2d(j, a), b_j = vertex_2d(j, b);
    return RigidMap2::aligning(b_j - a_j, b_i - a_i, (a_j + b_j) * 0.5,
                               (a_i + b_i) * 0.5);
}

// Teo §4.1: a vertex neighbour rotates into i's plane about the intersection line L_ij of
// the two planes, which passes through the shared vertex. That 3D rotation fixes L_ij's
// direction d, so in the reference planes it is the 2D rotation taking d's image in j to
// d's image in i, about the shared vertex.
RigidMap2 Crps::vertex_map(TriId i, TriId j, VertId v) const {
    const CrpsFrame &fi = m_frames[i], &fj = m_frames[j];
    Vec3d d = cross(fi.normal, fj.normal);
    if (length_squared(d) < 1e-24) {
        // Coplanar (or folded flat): both planes hold the same lines through v; align
        // them along one of i's edges from v.
        const auto &tri = m_triangles[i];
        const int c = tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
        const Vec2d e = fi.v[(c + 1) % 3] - fi.v[c];
        d = fi.rotation.transpose_times({e.x, 0, e.y});
    }
    const Vec2d d_i = xz(fi.rotation * d), d_j = xz(fj.rotation * d);
    return RigidMap2::aligning(d_j, d_i, vertex_2d(j, v), vertex_2d(i, v));
}

bool Crps::find_map(TriId i, TriId j, RigidMap2 *j_to_i) const {
    const auto nb = m_topo.neighbours(i);
    for (size_t k = 0; k < nb.size(); ++k)
        if (nb[k] == j) {
            *j_to_i = m_to_master[m_topo.nbr_row[i] + k];
            return true;
        }
    return false;
}

Vec2d Crps::to_2d(TriId t, Vec3d p_world) const {
    const CrpsFrame &f = m_frames[t];
    return xz(f.rotation * p_world) - f.centre;
}

Vec3d Crps::to_3d(TriId t, Vec2d p) const {
    const CrpsFrame &f = m_frames[t];
    return f.rotation.transpose_times({p.x + f.centre.x, f.y_offset, p.y + f.centre.y});
}

Vec2d Crps::barycentric_to_2d(TriId t, Vec3d b) const {
    const CrpsFrame &f = m_frames[t];
    return f.v[0] * b.x + f.v[1] * b.y + f.v[2] * b.z;
}

Vec3d Crps::to_barycentric(TriId t, Vec2d p) const {
    return barycentric_in(m_frames[t], p);
}

Vec3d barycentric_in(const CrpsFrame &f, Vec2d p) {
    const Vec2d e1 = f.v[1] - f.v[0], e2 = f.v[2] - f.v[0], r = p - f.v[0];
    const double det = cross(e1, e2);
    const double b1 = cross(r, e2) / det, b2 = cross(e1, r) / det;
    return {1.0 - b1 - b2, b1, b2};
}

}  // namespace pelage::sim
