#include "sim/geodesic/geodesic_mesh.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {
namespace {

double corner_angle(const CrpsFrame &f, int c) {
    const Vec2d a = f.v[(c + 1) % 3] - f.v[c], b = f.v[(c + 2) % 3] - f.v[c];
    return std::atan2(std::abs(cross(a, b)), dot(a, b));
}

}  // namespace

GeodesicMesh::GeodesicMesh(const Crps &crps, const GeodesicMeshOptions &options)
    : m_crps(&crps) {
    const Topology &topo = crps.topology();
    const size_t nt = crps.num_triangles();
    m_links.resize(nt);
    size_t nv = 0;
    for (TriId t = 0; t < nt; ++t)
        for (VertId v : crps.corners(t)) nv = std::max<size_t>(nv, v + 1);
    m_angle_sum.assign(nv, 0.0);
    m_pseudo_source.assign(nv, 0);

    for (TriId t = 0; t < nt; ++t) {
        const auto &ct = crps.corners(t);
        for (int k = 0; k < 3; ++k) {
            m_angle_sum[ct[k]] += corner_angle(crps.frame(t), k);
            const TriId g = topo.across(t, k);
            if (g == invalid_id) {
                // Paths may bend around both ends of a boundary (or non-manifold) edge.
                m_pseudo_source[ct[k]] = m_pseudo_source[ct[(k + 1) % 3]] = 1;
                continue;
            }
            const auto &cg = crps.corners(g);
            int kg = -1;
            for (int j = 0; j < 3; ++j) {
                const VertId a = cg[j], b = cg[(j + 1) % 3];
                if ((a == ct[k] && b == ct[(k + 1) % 3]) ||
                    (b == ct[k] && a == ct[(k + 1) % 3]))
                    kg = j;
            }
            RigidMap2 to_g;
            if (kg < 0 || !crps.find_map(g, t, &to_g)) {
                m_pseudo_source[ct[k]] = m_pseudo_source[ct[(k + 1) % 3]] = 1;
                continue;
            }
            m_links[t][k] = {g, static_cast<uint8_t>(kg), to_g};
        }
    }
    const double two_pi = 2 * 3.14159265358979323846;
    for (VertId v = 0; v < nv; ++v) {
        if (topo.fan_row.size() > v + 1 && !topo.fan_ordered[v]) m_pseudo_source[v] = 1;
        if (m_angle_sum[v] > two_pi + options.flat_tolerance) m_pseudo_source[v] = 1;
        m_num_pseudo_sources += m_pseudo_source[v];
    }
}

}  // namespace pelage::sim
