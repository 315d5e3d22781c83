#include "pattern/transfer/cell_cover.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/mesh/closest_point.h"

namespace pelage::pattern::transfer {

CellCover::CellCover(const sim::Surface &simulation, const std::vector<char> &reaches)
    : m_surface(&simulation) {
    const sim::TriangleMesh &m = simulation.mesh;
    const sim::Crps &crps = simulation.crps;
    const size_t nt = m.num_triangles();
    m_report.triangles = nt;
    m_report.pieces = crps.topology().num_components;
    // The cell-bearing triangles alone, for the closest-point grid; their ids back.
    sim::TriangleMesh bearing;
    bearing.positions = m.positions;
    std::vector<sim::TriId> bearing_tri;
    double area = 0, carried_area = 0;
    std::vector<char> carried_component(m_report.pieces, 0);
    for (sim::TriId t = 0; t < nt; ++t) {
        const double a = crps.frame(t).area;
        area += a;
        if (reaches[t]) {
            bearing.triangles.push_back(m.triangles[t]);
            bearing_tri.push_back(t);
        } else {
            carried_area += a;
            ++m_report.carried_triangles;
            carried_component[crps.topology().component[t]] = 1;
        }
    }
    const double share = area > 0 ? carried_area / area : 0;
    if (bearing_tri.empty()) {
        // No cells anywhere: nothing to carry to.
        m_report.carried_triangles = 0;
        m_report.without_cell_share = share;
        return;
    }
    if (m_report.carried_triangles == 0) return;
    m_report.carried_area_share = share;
    m_report.carried_pieces = static_cast<size_t>(
        std::count(carried_component.begin(), carried_component.end(), 1));

    m_slot.assign(nt, no_slot);
    std::vector<sim::TriId> carried_tri;
    for (sim::TriId t = 0; t < nt; ++t)
        if (!reaches[t]) {
            m_slot[t] = static_cast<uint32_t>(carried_tri.size());
            carried_tri.push_back(t);
        }
    m_carried.resize(carried_tri.size());
    std::vector<double> moved(carried_tri.size(), 0);
    const sim::ClosestPointGrid grid(bearing);
    const double tie = 1e-6 * m.bounds().diagonal();
    tbb::parallel_for(size_t(0), carried_tri.size(), [&](size_t i) {
        const sim::TriId t = carried_tri[i];
        const sim::Vec3d p[3] = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2)};
        // No normal, no tie for the corners (as surface_transfer.cpp places vertices);
        // the centroid's triangle faces like t where sheets of the surface touch.
        sim::MeshPoint corner[3];
        for (int k = 0; k < 3; ++k) {
            corner[k] = grid.closest_facing(p[k], {}, 0);
            moved[i] = std::max(moved[i], corner[k].distance);
        }
        const sim::Vec3d normal = normalize(m.face_normal_unnormalized(t));
        const sim::TriId candidates[4] = {
            grid.closest_facing((p[0] + p[1] + p[2]) / 3.0, normal, tie).tri,
            corner[0].tri, corner[1].tri, corner[2].tri};
        Carried &out = m_carried[i];
        for (sim::TriId c : candidates) {
            if (c == sim::invalid_id) continue;
            const sim::TriId s = bearing_tri[c];
            bool seen = false;
            for (uint32_t k = 0; k < out.n; ++k) seen |= out.c[k].tri == s;
            if (seen) continue;
            Candidate &cand = out.c[out.n++];
            cand.tri = s;
            for (int k = 0; k < 3; ++k) {
                const sim::Vec3d b =
                    crps.to_barycentric(s, crps.to_2d(s, corner[k].point));
                cand.b[k][0] = float(b.y);
                cand.b[k][1] = float(b.z);
            }
        }
    });
    const double diag = m.bounds().diagonal();
    for (double d : moved)
        m_report.max_carry_distance = std::max(m_report.max_carry_distance, d / diag);
}

SurfaceTransfer::Target CellCover::map(sim::TriId t, float b1, float b2) const {
    const Carried &r = m_carried[m_slot[t]];
    const float b0 = 1 - b1 - b2;
    SurfaceTransfer::Target best{r.c[0].tri, 0, 0};
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
        if (inside >= 0) break;  // nearest first: the centroid's closest triangle
    }
    if (best_inside < -1e-4f) {
        // Outside every candidate (a piece larger than the triangles it lies on): walk
        // across the edge the point lies beyond, in each triangle's plane, on the
        // cell-bearing surface only.
        const sim::TriangleMesh &m = m_surface->mesh;
        const sim::Crps &crps = m_surface->crps;
        const sim::Vec3d p = m.vertex(t, 0) * double(b0) + m.vertex(t, 1) * double(b1) +
                             m.vertex(t, 2) * double(b2);
        const sim::Topology &topo = crps.topology();
        sim::TriId at = best.tri, previous = sim::invalid_id;
        for (int step = 0; step < 256; ++step) {
            const sim::Vec3d b = crps.to_barycentric(at, crps.to_2d(at, p));
            const double coord[3] = {b.x, b.y, b.z};
            const int worst = int(std::min_element(coord, coord + 3) - coord);
            if (float(coord[worst]) > best_inside) {
                best_inside = float(coord[worst]);
                best = {at, float(b.y), float(b.z)};
            }
            if (coord[worst] >= -1e-6) break;
            // Corner `worst` is opposite edge (worst + 1) % 3.
            const sim::TriId next = topo.across(at, (worst + 1) % 3);
            if (next == sim::invalid_id || next == previous || carries(next)) break;
            previous = at;
            at = next;
        }
    }
    best.b1 = std::clamp(best.b1, 0.0f, 1.0f);
    best.b2 = std::clamp(best.b2, 0.0f, 1.0f - best.b1);
    return best;
}

}  // namespace pelage::pattern::transfer
