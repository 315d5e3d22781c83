#include "renderer/fur/clump_guides.h"

#include <cmath>

#include "renderer/fur/fur_hash.h"
#include "renderer/fur/strand_shape.h"

namespace pelage::renderer {

namespace {
constexpr float clump_pi = 3.14159265358979323846f;
}

ClumpGuides::ClumpGuides(const FurParams &params, const SkinMesh &mesh,
                         const RootSampler &roots)
    : m_params(params) {
    if (params.clump <= 0 && !params.vary(FurParams::Groomed::clump).varies()) return;
    const double r = params.clump_radius;
    const uint64_t seed = params.seed ^ 0x5bd1e995ull;  // guides' own root stream
    const uint64_t n = std::min<uint64_t>(
        candidate_count(roots.area() / (clump_pi * r * r), seed), params.max_strands);
    m_cell = float(2 * r);
    const int S = params.segments;
    m_roots.resize(n);
    m_lines.resize(n * size_t(S + 1));
    for (uint64_t i = 0; i < n; ++i) {
        Vec3f p, nrm;
        const SurfacePoint root = roots.sample(seed, i);
        roots.point_normal(root, &p, &nrm);
        const StrandRandom rnd{float(uniform(seed, Stream::guides, i, 0)),
                               float(uniform(seed, Stream::guides, i, 1)),
                               float(uniform(seed, Stream::guides, i, 2))};
        grow_centre_line(params, coat_groom(params), p, nrm, comb_at(params, mesh, root),
                         params.length, rnd, &m_lines[i * (S + 1)]);
        m_roots[i] = p;
        m_grid[key(p)].push_back(uint32_t(i));
    }
}

uint64_t ClumpGuides::key(Vec3f p) const {
    // 21 bits per axis, wrapping: a collision only adds candidates, never loses one.
    auto c = [&](float x) {
        return uint64_t(int64_t(std::floor(x / m_cell))) & 0x1fffff;
    };
    return c(p.x) | c(p.y) << 21 | c(p.z) << 42;
}

void ClumpGuides::pull(Vec3f *line, float clump, float scale) const {
    if (m_roots.empty() || clump <= 0) return;
    const Vec3f p = line[0];
    float best_d2 = m_cell * m_cell;
    int64_t best = -1;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                const auto it =
                    m_grid.find(key(p + Vec3f{dx * m_cell, dy * m_cell, dz * m_cell}));
                if (it == m_grid.end()) continue;
                for (uint32_t g : it->second) {
                    const Vec3f e = m_roots[g] - p;
                    const float d2 = e.x * e.x + e.y * e.y + e.z * e.z;
                    if (d2 < best_d2 || (d2 == best_d2 && g < best)) {
                        best_d2 = d2;
                        best = g;
                    }
                }
            }
    if (best < 0) return;
    const int S = m_params.segments;
    const Vec3f *g = &m_lines[size_t(best) * (S + 1)];
    // The strand keeps its root; its shape follows the guide's, offset to its own root.
    const Vec3f offset = p - g[0];
    for (int k = 1; k <= S; ++k) {
        const float w = clump * float(k) / float(S);
        const Vec3f gk = scale == 1 ? g[k] : g[0] + (g[k] - g[0]) * scale;
        const Vec3f target = gk + offset * (1 - float(k) / float(S));
        line[k] = line[k] * (1 - w) + target * w;
    }
}

}  // namespace pelage::renderer
