#include "sim/geodesic/geodesic_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "sim/core/disjoint_sets.h"

namespace pelage::sim {
namespace {

double corner_angle(const CrpsFrame &f, int c) {
    const Vec2d a = f.v[(c + 1) % 3] - f.v[c], b = f.v[(c + 2) % 3] - f.v[c];
    return std::atan2(std::abs(cross(a, b)), dot(a, b));
}

int corner_of(const std::array<VertId, 3> &c, VertId v) {
    return c[0] == v ? 0 : (c[1] == v ? 1 : (c[2] == v ? 2 : -1));
}

}  // namespace

GeodesicMesh::GeodesicMesh(const Crps &crps, const GeodesicMeshOptions &options)
    : m_crps(&crps) {
    const Topology &topo = crps.topology();
    const size_t nt = crps.num_triangles();
    m_links.resize(nt);
    m_corners.resize(nt);
    size_t nv = 0;
    for (TriId t = 0; t < nt; ++t) {
        m_corners[t] = crps.corners(t);
        for (VertId v : crps.corners(t)) nv = std::max<size_t>(nv, v + 1);
    }

    // --- Pinch vertices: one vertex per group of faces joined across edges at it ---
    size_t next = nv;
    for (VertId v = 0; v < nv && v + 1 < topo.fan_row.size(); ++v) {
        if (topo.fan_ordered[v]) continue;
        const auto fan = topo.fan_of(v);
        DisjointSets group(fan.size());
        auto root = [&](uint32_t a) { return group.find(a); };
        for (size_t i = 0; i < fan.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                const auto &c = crps.corners(fan[i]);
                if (c[k] != v && c[(k + 1) % 3] != v) continue;  // an edge at v
                const TriId g = topo.across(fan[i], k);
                const auto it = std::find(fan.begin(), fan.end(), g);
                if (g != invalid_id && it != fan.end())
                    group.unite(uint32_t(i), uint32_t(it - fan.begin()));
            }
        std::vector<uint32_t> id_of_root(fan.size(), invalid_id);
        bool first = true;
        for (size_t i = 0; i < fan.size(); ++i) {
            const uint32_t r = root(uint32_t(i));
            if (id_of_root[r] == invalid_id) {
                id_of_root[r] = first ? v : static_cast<VertId>(next++);
                first = false;
            }
            const int c = corner_of(m_corners[fan[i]], v);
            m_corners[fan[i]][c] = id_of_root[r];
        }
    }
    nv = next;
    m_angle_sum.assign(nv, 0.0);
    m_pseudo_source.assign(nv, 0);
    m_fan_row.assign(nv + 1, 0);

    for (TriId t = 0; t < nt; ++t) {
        const auto &ct = m_corners[t];
        for (int k = 0; k < 3; ++k) {
            ++m_fan_row[ct[k] + 1];
            m_angle_sum[ct[k]] += corner_angle(crps.frame(t), k);
            const TriId g = topo.across(t, k);
            if (g == invalid_id) {
                // Paths may bend around both ends of a boundary (or non-manifold) edge.
                m_pseudo_source[ct[k]] = m_pseudo_source[ct[(k + 1) % 3]] = 1;
                continue;
            }
            const auto &cg = crps.corners(g), &co = crps.corners(t);
            int kg = -1;
            for (int j = 0; j < 3; ++j) {
                const VertId a = cg[j], b = cg[(j + 1) % 3];
                if ((a == co[k] && b == co[(k + 1) % 3]) ||
                    (b == co[k] && a == co[(k + 1) % 3]))
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
    for (size_t v = 0; v < nv; ++v) m_fan_row[v + 1] += m_fan_row[v];
    m_fan.resize(m_fan_row[nv]);
    std::vector<uint32_t> fill(m_fan_row.begin(), m_fan_row.end() - 1);
    for (TriId t = 0; t < nt; ++t)
        for (VertId v : m_corners[t]) m_fan[fill[v]++] = t;

    const double two_pi = 2 * 3.14159265358979323846;
    for (size_t v = 0; v < nv; ++v) {
        if (m_angle_sum[v] > two_pi + options.flat_tolerance) m_pseudo_source[v] = 1;
        m_num_pseudo_sources += m_pseudo_source[v];
    }
}

}  // namespace pelage::sim
