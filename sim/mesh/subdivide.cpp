#include "sim/mesh/subdivide.h"

#include <map>
#include <set>
#include <utility>

namespace pelage::sim {

TriangleMesh subdivide(const TriangleMesh &m, Subdivision kind) {
    std::map<std::pair<VertId, VertId>, std::vector<VertId>> opposite;  // per edge
    for (const auto &t : m.triangles)
        for (int k = 0; k < 3; ++k) {
            const VertId a = t[k], b = t[(k + 1) % 3];
            opposite[{std::min(a, b), std::max(a, b)}].push_back(t[(k + 2) % 3]);
        }
    TriangleMesh out;
    out.positions = m.positions;
    if (kind == Subdivision::loop) {
        std::vector<std::set<VertId>> ring(m.num_vertices());
        std::vector<char> boundary(m.num_vertices(), 0);
        for (const auto &[e, opp] : opposite) {
            ring[e.first].insert(e.second);
            ring[e.second].insert(e.first);
            if (opp.size() != 2) boundary[e.first] = boundary[e.second] = 1;
        }
        for (VertId v = 0; v < m.num_vertices(); ++v) {
            const size_t n = ring[v].size();
            if (boundary[v] || n < 3) continue;
            const double beta = n == 3 ? 3.0 / 16 : 3.0 / (8.0 * n);
            Vec3d sum{0, 0, 0};
            for (VertId u : ring[v]) sum += m.positions[u];
            out.positions[v] = m.positions[v] * (1 - n * beta) + sum * beta;
        }
    }
    std::map<std::pair<VertId, VertId>, VertId> middle;
    auto mid = [&](VertId a, VertId b) {
        const std::pair<VertId, VertId> e{std::min(a, b), std::max(a, b)};
        const auto it = middle.find(e);
        if (it != middle.end()) return it->second;
        const auto &opp = opposite[e];
        Vec3d p = (m.positions[a] + m.positions[b]) * 0.5;
        if (kind == Subdivision::loop && opp.size() == 2)
            p = (m.positions[a] + m.positions[b]) * (3.0 / 8) +
                (m.positions[opp[0]] + m.positions[opp[1]]) * (1.0 / 8);
        out.positions.push_back(p);
        const VertId id = static_cast<VertId>(out.positions.size() - 1);
        middle[e] = id;
        return id;
    };
    for (const auto &t : m.triangles) {
        const VertId ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
        out.triangles.push_back({t[0], ab, ca});
        out.triangles.push_back({ab, t[1], bc});
        out.triangles.push_back({ca, bc, t[2]});
        out.triangles.push_back({ab, bc, ca});
    }
    for (size_t i = 0; i < out.triangles.size(); ++i)
        out.source_face.push_back(static_cast<uint32_t>(i));
    return out;
}

}  // namespace pelage::sim
