#include "pattern/transfer/surface_transfer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/core/input_error.h"

namespace pelage::pattern::transfer {
namespace {

using sim::Vec3d;

std::vector<char> used_vertices(const sim::TriangleMesh &m) {
    std::vector<char> used(m.num_vertices(), 0);
    for (const auto &t : m.triangles)
        for (sim::VertId v : t) used[v] = 1;
    return used;
}

sim::Bounds3 used_bounds(const sim::TriangleMesh &m, const std::vector<char> &used) {
    sim::TriangleMesh corners;
    for (size_t v = 0; v < m.num_vertices(); ++v)
        if (used[v]) corners.positions.push_back(m.positions[v]);
    return corners.bounds();
}

}  // namespace

SurfaceTransfer::SurfaceTransfer(const sim::Surface &simulation,
                                 const sim::TriangleMesh &render,
                                 const std::string &cells_path,
                                 const std::string &render_path) {
    const sim::TriangleMesh &sm = simulation.mesh;
    // Only the vertices triangles use: the mesh of one object of an OBJ keeps every
    // vertex of the file.
    const std::vector<char> r_used = used_vertices(render);
    const sim::Bounds3 sb = used_bounds(sm, used_vertices(sm)),
                       rb = used_bounds(render, r_used);
    const double s_diag = sb.diagonal(), r_diag = rb.diagonal();
    const Vec3d s_centre = (sb.lo + sb.hi) * 0.5, r_centre = (rb.lo + rb.hi) * 0.5;
    double scale = 1;
    Vec3d shift{0, 0, 0};
    if (std::abs(r_diag / s_diag - 1) > 0.02 ||
        length(r_centre - s_centre) > 0.02 * s_diag) {
        scale = s_diag / r_diag;
        shift = s_centre - r_centre * scale;
        m_similarity = true;
    }
    m_scale = float(scale);
    auto place = [&](Vec3d p) { return p * scale + shift; };

    const sim::ClosestPointGrid grid(sm);
    std::vector<sim::MeshPoint> at_vertex(render.num_vertices());
    tbb::parallel_for(size_t(0), render.num_vertices(), [&](size_t v) {
        // No normal, no tie: the closest triangle, ties to the lowest id (closest()
        // differs only where a triangle has no normal, as the vertices are placed).
        if (r_used[v])
            at_vertex[v] = grid.closest_facing(place(render.positions[v]), {}, 0);
    });
    for (const auto &h : at_vertex)
        if (std::isfinite(h.distance))
            m_max_deviation = std::max(m_max_deviation, h.distance / s_diag);
    if (m_max_deviation > 0.02)
        throw InputError(cells_path, 0, "",
                         "grown on another surface: the render mesh " + render_path +
                             " lies up to " + std::to_string(100 * m_max_deviation) +
                             " % of its size away from it (at most 2 % is taken for the "
                             "same shape)");

    m_crps = &simulation.crps;
    m_tris.resize(render.num_triangles());
    m_placed.resize(render.num_triangles());
    tbb::parallel_for(size_t(0), render.num_triangles(), [&](size_t t) {
        const auto &tri = render.triangles[t];
        const Vec3d corner[3] = {at_vertex[tri[0]].point, at_vertex[tri[1]].point,
                                 at_vertex[tri[2]].point};
        const Vec3d centroid =
            (place(render.positions[tri[0]]) + place(render.positions[tri[1]]) +
             place(render.positions[tri[2]])) /
            3.0;
        const Vec3d normal = normalize(render.face_normal_unnormalized(sim::TriId(t)));
        const double tie = 1e-6 * s_diag;
        sim::TriId candidates[4] = {grid.closest_facing(centroid, normal, tie).tri,
                                    at_vertex[tri[0]].tri, at_vertex[tri[1]].tri,
                                    at_vertex[tri[2]].tri};
        RenderTriangle &out = m_tris[t];
        for (int k = 0; k < 3; ++k) m_placed[t][k] = place(render.positions[tri[k]]);
        for (sim::TriId c : candidates) {
            if (c == sim::invalid_id) continue;
            bool seen = false;
            for (uint32_t k = 0; k < out.n; ++k) seen |= out.c[k].tri == c;
            if (seen) continue;
            Candidate &cand = out.c[out.n++];
            cand.tri = c;
            for (int k = 0; k < 3; ++k) {
                const sim::Vec3d b = simulation.crps.to_barycentric(
                    c, simulation.crps.to_2d(c, corner[k]));
                cand.b[k][0] = float(b.y);
                cand.b[k][1] = float(b.z);
            }
        }
    });
}

SurfaceTransfer::Target SurfaceTransfer::map(uint32_t t, float b1, float b2) const {
    const RenderTriangle &r = m_tris[t];
    const float b0 = 1 - b1 - b2;
    Target best{r.c[0].tri, 0, 0};
    float best_inside = -std::numeric_limits<float>::infinity();
    for (uint32_t k = 0; k < r.n; ++k) {
        const Candidate &c = r.c[k];
        const float u = b0 * c.b[0][0] + b1 * c.b[1][0] + b2 * c.b[2][0];
        const float v = b0 * c.b[0][1] + b1 * c.b[1][1] + b2 * c.b[2][1];
        const float inside = std::min({u, v, 1 - u - v});
        if (inside > best_inside) {
            best_inside = inside;
            best = {c.tri, u, v};
        }
        // Candidates come nearest first (the centroid's closest triangle): the first
        // that holds the point wins, so a fold of the surface behind it never does.
        if (inside >= 0) break;
    }
    if (best_inside < -1e-4f && best.tri != sim::invalid_id) {
        // Outside every candidate: walk across the edge the point lies beyond, towards
        // the most negative coordinate's opposite edge, in each triangle's plane.
        const auto &c = m_placed[t];
        const sim::Vec3d p = c[0] * double(b0) + c[1] * double(b1) + c[2] * double(b2);
        const sim::Topology &topo = m_crps->topology();
        sim::TriId at = best.tri, previous = sim::invalid_id;
        for (int step = 0; step < 256; ++step) {
            const sim::Vec3d b = m_crps->to_barycentric(at, m_crps->to_2d(at, p));
            const double coord[3] = {b.x, b.y, b.z};
            const int worst = int(std::min_element(coord, coord + 3) - coord);
            const float inside = float(coord[worst]);
            if (inside > best_inside) {
                best_inside = inside;
                best = {at, float(b.y), float(b.z)};
            }
            if (coord[worst] >= -1e-6) break;
            // Corner `worst` is opposite edge (worst + 1) % 3.
            const sim::TriId next = topo.across(at, (worst + 1) % 3);
            if (next == sim::invalid_id || next == previous) break;  // a boundary, a fold
            previous = at;
            at = next;
        }
    }
    // Onto the triangle: a point of a render triangle that straddles simulation
    // triangles may fall a little outside all of them.
    best.b1 = std::clamp(best.b1, 0.0f, 1.0f);
    best.b2 = std::clamp(best.b2, 0.0f, 1.0f - best.b1);
    return best;
}

}  // namespace pelage::pattern::transfer
