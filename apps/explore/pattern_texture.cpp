#include "apps/explore/pattern_texture.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "pattern/mosaic/cell_table.h"
#include "pattern/mosaic/closest_cell.h"

namespace pelage::renderer::explore {
namespace {

struct Placement {
    std::vector<int> k, x, y;  // per triangle
};

// Shelf packing of squares sorted by size (largest first): false when they overflow.
bool place(const std::vector<sim::TriId> &order, const std::vector<double> &edge,
           double texel, int size, Placement *p) {
    int x = 0, y = 0, shelf = 0;
    for (sim::TriId t : order) {
        const int k = std::max(2, int(std::ceil(edge[t] / texel)));
        if (k > size) return false;
        if (x + k > size) {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        if (y + k > size) return false;
        p->k[t] = k;
        p->x[t] = x;
        p->y[t] = y;
        x += k;
        shelf = std::max(shelf, k);
    }
    return true;
}

}  // namespace

TypeTextureLayout layout_type_texture(const sim::TriangleMesh &mesh, int size) {
    const size_t n = mesh.num_triangles();
    if (size < 2 || double(size) < 2 * std::sqrt(double(n)))
        throw std::invalid_argument("layout_type_texture: " + std::to_string(size) +
                                    " texels across cannot hold " + std::to_string(n) +
                                    " triangles");
    std::vector<double> edge(n);
    for (size_t t = 0; t < n; ++t) {
        const auto &tri = mesh.triangles[t];
        double e = 0;
        for (int c = 0; c < 3; ++c)
            e = std::max(
                e, length(mesh.positions[tri[(c + 1) % 3]] - mesh.positions[tri[c]]));
        edge[t] = e;
    }
    std::vector<sim::TriId> order(n);
    std::iota(order.begin(), order.end(), sim::TriId(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](sim::TriId a, sim::TriId b) { return edge[a] > edge[b]; });
    Placement p{std::vector<int>(n), std::vector<int>(n), std::vector<int>(n)};
    // The smallest texel that fits, by bisection: the longest edge per texel makes
    // every tile 2 × 2, which the size check lets fit.
    const double longest = n ? edge[order.front()] : 1.0;
    double lo = 0, hi = std::max(longest, 1e-30);
    Placement fits = p;
    if (!place(order, edge, hi, size, &fits))
        throw std::invalid_argument("layout_type_texture: tiles do not fit");
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid > 0 && place(order, edge, mid, size, &p)) {
            hi = mid;
            fits = p;
        } else {
            lo = mid;
        }
    }
    TypeTextureLayout l;
    l.size = size;
    l.texel_length = hi;
    l.corner_uvs.resize(6 * n);
    const float s = float(size);
    for (size_t t = 0; t < n; ++t) {
        const float x0 = float(fits.x[t]) + 0.5f, y0 = float(fits.y[t]) + 0.5f,
                    d = float(fits.k[t] - 1);
        const float uv[6] = {x0 / s, y0 / s, (x0 + d) / s, y0 / s, x0 / s, (y0 + d) / s};
        std::copy(uv, uv + 6, &l.corner_uvs[6 * t]);
        const int k = fits.k[t];
        auto at = [&](int i, int j) {
            return uint32_t(fits.y[t] + j) * uint32_t(size) + uint32_t(fits.x[t] + i);
        };
        for (int j = 0; j < k; ++j)
            for (int i = k - j; i < k; ++i) {
                const int e = i + j - (k - 1);
                l.fill.push_back({at(i, j), at(i - e / 2, j - (e - e / 2))});
            }
        for (int j = 0; j < k; ++j)
            for (int i = 0; i + j <= k - 1; ++i) {
                l.texel.push_back(uint32_t(fits.y[t] + j) * uint32_t(size) +
                                  uint32_t(fits.x[t] + i));
                l.tri.push_back(sim::TriId(t));
                l.b1.push_back(float(i) / float(k - 1));
                l.b2.push_back(float(j) / float(k - 1));
            }
    }
    return l;
}

SampleTargets map_samples(const TypeTextureLayout &layout,
                          const pattern::transfer::SurfaceTransfer &transfer) {
    SampleTargets out(layout.texel.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096),
                      [&](const tbb::blocked_range<size_t> &r) {
                          for (size_t i = r.begin(); i < r.end(); ++i)
                              out[i] =
                                  transfer.map(layout.tri[i], layout.b1[i], layout.b2[i]);
                      });
    return out;
}

std::vector<uint8_t> type_texture(const TypeTextureLayout &layout, const sim::Crps &crps,
                                  const sim::CellsData &data,
                                  const SampleTargets *targets) {
    if (data.num_triangles() != crps.num_triangles())
        throw std::invalid_argument("type_texture: the cells lie on another surface");
    std::vector<pattern::mosaic::CellOnSurface> list;
    list.reserve(data.num_cells());
    for (sim::TriId t = 0; t < data.num_triangles(); ++t)
        for (uint32_t k = data.cell_row[t]; k < data.cell_row[t + 1]; ++k)
            list.push_back({t, data.x[k], data.z[k], data.id[k], data.type[k]});
    const pattern::mosaic::CellTable table =
        pattern::mosaic::make_cell_table(data.num_triangles(), list);
    const pattern::mosaic::ClosestCellIndex index(crps, table);
    std::vector<uint8_t> out(size_t(layout.size) * size_t(layout.size), no_type);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, layout.texel.size(), 4096),
        [&](const tbb::blocked_range<size_t> &r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                const pattern::transfer::SurfaceTransfer::Target at =
                    targets ? (*targets)[i]
                            : pattern::transfer::SurfaceTransfer::Target{
                                  layout.tri[i], layout.b1[i], layout.b2[i]};
                const sim::CrpsFrame &f = crps.frame(at.tri);
                const sim::Vec2d e1 = f.v[1] - f.v[0], e2 = f.v[2] - f.v[0];
                const pattern::mosaic::Vec2f q{
                    float(f.v[0].x + at.b1 * e1.x + at.b2 * e2.x),
                    float(f.v[0].y + at.b1 * e1.y + at.b2 * e2.y)};
                const pattern::mosaic::ClosestCell c = index.find_nearest(at.tri, q);
                if (c.index != pattern::mosaic::ClosestCell::none)
                    out[layout.texel[i]] = table.type[c.index];
            }
        });
    for (const auto &[to, from] : layout.fill) out[to] = out[from];
    return out;
}

}  // namespace pelage::renderer::explore
