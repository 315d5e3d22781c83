#include "sim/cells_report/stripe_alignment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pelage::sim {

namespace {

double quantile(const std::vector<double> &sorted, double q) {
    if (sorted.empty()) return 0;
    const double x = q * double(sorted.size() - 1);
    const size_t i = static_cast<size_t>(x);
    const double f = x - double(i);
    return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}

}  // namespace

StripeAlignment measure_stripe_alignment(const CellsData &d, const Crps &crps,
                                         const TangentField &field, double window) {
    if (crps.num_triangles() != d.num_triangles() || field.a.size() != d.num_triangles())
        throw std::invalid_argument("stripe alignment: surface, field and cells differ");
    StripeAlignment out;
    const int F = find_type(d, "F", 0), B = find_type(d, "B", 1);
    const size_t n = d.num_cells(), nt = d.num_triangles();
    if (F < 0 || B < 0 || F == B || n == 0) return out;
    const double spacing = std::sqrt(d.area() / double(n));
    const double delta = 1.5 * spacing, R = window * spacing;
    std::vector<double> bound(nt);
    for (TriId t = 0; t < nt; ++t)
        bound[t] = std::max({length(d.frames[t].v[0]), length(d.frames[t].v[1]),
                             length(d.frames[t].v[2])});

    struct Placed {
        Vec2d p;
        bool f, own;
    };
    std::vector<std::pair<TriId, RigidMap2>> queue;
    std::vector<uint32_t> seen(nt, ~0u);
    std::vector<Placed> placed;
    std::vector<Vec2d> gradient;
    std::vector<double> coherence;
    const Topology &topo = crps.topology();
    for (TriId t = 0; t < nt; ++t) {
        if (d.cell_row[t] == d.cell_row[t + 1] || !(length_squared(field.a[t]) > 0))
            continue;
        // Triangles within reach, unfolded across edges into t's frame (first path).
        const double reach = bound[t] + R + delta;
        queue.assign(1, {t, RigidMap2{}});
        seen[t] = t;
        for (size_t head = 0; head < queue.size(); ++head) {
            const auto [u, G] = queue[head];
            const auto nbrs = topo.primary_neighbours(u);
            const auto maps = crps.to_master(u);
            for (size_t k = 0; k < nbrs.size(); ++k) {
                const TriId j = nbrs[k];
                if (seen[j] == t) continue;
                const RigidMap2 M = compose(G, maps[k]);
                if (std::hypot(M.ax, M.ay) > reach + bound[j]) continue;
                seen[j] = t;
                queue.push_back({j, M});
            }
        }
        placed.clear();
        for (const auto &[j, M] : queue)
            for (uint32_t c = d.cell_row[j]; c < d.cell_row[j + 1]; ++c)
                if (d.type[c] == F || d.type[c] == B)
                    placed.push_back({M.apply({d.x[c], d.z[c]}), d.type[c] == F, j == t});
        // Each placed cell's indicator gradient: Σ (χ_q − χ_p)(q − p) over its
        // neighbours within δ (a least-squares gradient up to a constant factor).
        gradient.assign(placed.size(), Vec2d{});
        for (size_t a = 0; a < placed.size(); ++a)
            for (size_t b = a + 1; b < placed.size(); ++b) {
                if (placed[a].f == placed[b].f) continue;
                const Vec2d e = placed[b].p - placed[a].p;
                if (length_squared(e) >= delta * delta) continue;
                const Vec2d g = placed[b].f ? e : e * -1.0;  // towards F
                gradient[a] += g;
                gradient[b] += g;
            }
        // t's own cells come first (queue[0] is t, unmoved), in cell order.
        const Vec2d A = field.a[t] / length(field.a[t]);
        for (size_t k = 0; k < placed.size() && placed[k].own; ++k) {
            if (!(length_squared(gradient[k]) > 0)) continue;  // not on a boundary
            const Vec2d p = placed[k].p;
            double xx = 0, xy = 0, yy = 0;
            for (size_t q = 0; q < placed.size(); ++q) {
                if (length_squared(placed[q].p - p) > R * R) continue;
                const Vec2d g = gradient[q];
                xx += g.x * g.x;
                xy += g.x * g.y;
                yy += g.y * g.y;
            }
            // Dominant eigenvector of [[xx, xy], [xy, yy]]: the boundary's normal at
            // angle ½·atan2(2xy, xx − yy); the stripe runs perpendicular to it.
            const double normal = 0.5 * std::atan2(2 * xy, xx - yy);
            const Vec2d stripe{-std::sin(normal), std::cos(normal)};
            const double cosine = std::min(1.0, std::abs(dot(stripe, A)));
            out.angles.push_back(std::acos(cosine) * 180 / 3.14159265358979323846);
            coherence.push_back(std::hypot(xx - yy, 2 * xy) / (xx + yy));
        }
    }
    out.samples = out.angles.size();
    std::vector<double> sorted = out.angles;
    std::sort(sorted.begin(), sorted.end());
    out.q1 = quantile(sorted, 0.25);
    out.median = quantile(sorted, 0.5);
    out.q3 = quantile(sorted, 0.75);
    std::sort(coherence.begin(), coherence.end());
    out.coherence = quantile(coherence, 0.5);
    return out;
}

}  // namespace pelage::sim
