#include "pattern/mosaic/mosaic_lod.h"

#include <algorithm>
#include <cmath>

#include "pattern/mosaic/subdivision.h"

namespace pelage::pattern::mosaic {

constexpr int channels = FilteredLook::channels;

MosaicLod::MosaicLod(const sim::Surface &surface, const ClosestCellIndex &index,
                     const std::function<FilteredLook(uint32_t cell)> &look_of,
                     size_t num_types) {
    const sim::Crps &crps = surface.crps;
    const sim::TriangleMesh &mesh = surface.mesh;
    const CellTable &cells = index.cells();
    const size_t nt = crps.num_triangles();
    double total_area = 0;
    for (sim::TriId t = 0; t < nt; ++t) total_area += crps.frame(t).area;
    // The grid: about four samples per cell spacing along the triangle's longest edge.
    const double spacing =
        std::sqrt(total_area / double(std::max<size_t>(cells.size(), 1)));

    m_tris.resize(nt);
    m_means.resize(nt);
    m_dominant.assign(nt, 0);
    std::vector<double> type_area(num_types);
    for (sim::TriId t = 0; t < nt; ++t) {
        const sim::CrpsFrame &f = crps.frame(t);
        double size = 0;
        for (int c = 0; c < 3; ++c) {
            const sim::Vec2d e = f.v[(c + 1) % 3] - f.v[c];
            size = std::max(size, std::sqrt(e.x * e.x + e.y * e.y));
        }
        m_tris[t].inv_size = size > 0 ? float(1 / size) : 0.0f;
        const auto n = uint32_t(std::clamp(std::ceil(4 * size / spacing), 4.0, 16.0));
        double sum[channels] = {0, 0, 0, 0, 0};
        std::fill(type_area.begin(), type_area.end(), 0.0);
        uint32_t samples = 0;
        for (uint32_t i = 0; i < n; ++i)
            for (uint32_t j = 0; i + j < n; ++j)
                for (bool upper : {false, true}) {
                    if (upper && i + j + 1 >= n) continue;  // the last row has no upper
                    const auto s = sub_triangle(n, i, j, upper);
                    const float b1 = float((s[0][0] + s[1][0] + s[2][0]) / 3),
                                b2 = float((s[0][1] + s[1][1] + s[2][1]) / 3);
                    const ClosestCell c = index.find_nearest(t, b1, b2);
                    if (c.index == ClosestCell::none) continue;
                    FilteredLook look = look_of(c.index);
                    for (int k = 0; k < channels; ++k) sum[k] += look.v[k];
                    const uint8_t type = cells.type[c.index];
                    if (type < num_types) type_area[type] += 1;
                    ++samples;
                }
        for (int k = 0; k < channels; ++k)
            m_means[t].v[k] = samples ? float(sum[k] / samples) : 0.0f;
        // A triangle with no cell in reach (a component without cells) keeps the
        // exact path, which leaves the material's defaults, at every footprint.
        if (samples == 0) m_tris[t].inv_size = 0;
        m_dominant[t] = uint32_t(std::max_element(type_area.begin(), type_area.end()) -
                                 type_area.begin());
    }

    // The least size among the triangles that filter at all (1 / the largest inv_size).
    float largest_inv = 0;
    for (const Triangle &tri : m_tris) largest_inv = std::max(largest_inv, tri.inv_size);
    m_smallest = largest_inv > 0 ? 1 / largest_inv : 0.0f;

    // Per vertex: the area-weighted mean of its triangles' means.
    std::vector<double> vertex(channels * mesh.num_vertices(), 0.0),
        weight(mesh.num_vertices(), 0.0);
    for (sim::TriId t = 0; t < nt; ++t)
        for (sim::VertId v : mesh.triangles[t]) {
            const double a = m_tris[t].inv_size > 0 ? crps.frame(t).area : 0.0;
            weight[v] += a;
            for (int k = 0; k < channels; ++k)
                vertex[channels * v + k] += a * m_means[t].v[k];
        }
    for (sim::TriId t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c) {
            const sim::VertId v = mesh.triangles[t][c];
            for (int k = 0; k < channels; ++k)
                m_tris[t].corner[c][k] = weight[v] > 0
                                             ? float(vertex[channels * v + k] / weight[v])
                                             : m_means[t].v[k];
        }
}

FilteredLook MosaicLod::at(uint32_t t, float b1, float b2) const {
    const Triangle &tri = m_tris[t];
    const float b0 = 1 - b1 - b2;
    FilteredLook out;
    for (int k = 0; k < channels; ++k)
        out.v[k] = b0 * tri.corner[0][k] + b1 * tri.corner[1][k] + b2 * tri.corner[2][k];
    return out;
}

}  // namespace pelage::pattern::mosaic
