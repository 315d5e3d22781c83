#include "renderer/fur/clump_guides.h"

#include <algorithm>
#include <cmath>
#include <utility>

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
    std::vector<std::pair<uint64_t, uint32_t>> by_cell(n);
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
        by_cell[i] = {key(p), uint32_t(i)};
    }
    std::sort(by_cell.begin(), by_cell.end());
    size_t cells = 0;
    for (size_t k = 0; k < n; ++k)
        cells += k == 0 || by_cell[k].first != by_cell[k - 1].first;
    size_t slots = 1;
    while (slots < 2 * cells) slots *= 2;
    m_slot_key.assign(slots, 0);
    m_slot_begin.assign(slots, 0);
    m_slot_end.assign(slots, 0);
    m_members.resize(n);
    for (size_t k = 0; k < n; ++k) {
        m_members[k] = by_cell[k].second;
        if (k > 0 && by_cell[k].first == by_cell[k - 1].first) continue;
        size_t s = mix64(by_cell[k].first) & (slots - 1);
        while (m_slot_key[s] != 0) s = (s + 1) & (slots - 1);
        m_slot_key[s] = by_cell[k].first + 1;
        m_slot_begin[s] = uint32_t(k);
        size_t e = k + 1;
        while (e < n && by_cell[e].first == by_cell[k].first) ++e;
        m_slot_end[s] = uint32_t(e);
    }
}

bool ClumpGuides::cell(uint64_t key, uint32_t *begin, uint32_t *end) const {
    const size_t mask = m_slot_key.size() - 1;
    for (size_t s = mix64(key) & mask;; s = (s + 1) & mask) {
        if (m_slot_key[s] == 0) return false;
        if (m_slot_key[s] == key + 1) {
            *begin = m_slot_begin[s];
            *end = m_slot_end[s];
            return true;
        }
    }
}

uint64_t ClumpGuides::key(Vec3f p) const {
    // 21 bits per axis, wrapping: a collision only adds candidates, never loses one.
    auto c = [&](float x) {
        return uint64_t(int64_t(std::floor(x / m_cell))) & 0x1fffff;
    };
    return c(p.x) | c(p.y) << 21 | c(p.z) << 42;
}

int64_t ClumpGuides::nearest(Vec3f p) const {
    if (m_roots.empty()) return -1;
    float best_d2 = m_cell * m_cell;
    int64_t best = -1;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                uint32_t begin, end;
                if (!cell(key(p + Vec3f{dx * m_cell, dy * m_cell, dz * m_cell}), &begin,
                          &end))
                    continue;
                for (uint32_t k = begin; k != end; ++k) {
                    const uint32_t g = m_members[k];
                    const Vec3f e = m_roots[g] - p;
                    const float d2 = e.x * e.x + e.y * e.y + e.z * e.z;
                    if (d2 < best_d2 || (d2 == best_d2 && g < best)) {
                        best_d2 = d2;
                        best = g;
                    }
                }
            }
    return best;
}

void ClumpGuides::pull(Vec3f *line, float clump, float scale) const {
    if (m_roots.empty() || clump <= 0) return;
    const Vec3f p = line[0];
    const int64_t best = nearest(p);
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
