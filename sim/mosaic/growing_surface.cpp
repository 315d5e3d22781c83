#include "sim/mosaic/growing_surface.h"

namespace pelage::sim {

namespace {

TriangleMesh with_positions(const TriangleMesh &rest, std::vector<Vec3d> positions) {
    TriangleMesh m;
    m.positions = std::move(positions);
    m.triangles = rest.triangles;
    return m;
}

}  // namespace

GrowingSurface::GrowingSurface(const TriangleMesh &rest, const Crps &rest_crps,
                               GrowthShape shape)
    : m_mesh(with_positions(rest, shape.at(shape.first_age()))),
      m_rest_positions(rest.positions),
      m_crps(m_mesh, rest_crps.topology()),
      m_shape(std::move(shape)),
      m_age(m_shape.first_age()) {}

void GrowingSurface::reshape(double age, Cells &cells) {
    m_age = age;
    m_mesh.positions = m_shape.at(age);
    Crps next(m_mesh, m_crps.topology());
    carry_cells(m_crps, next, cells);
    m_crps = std::move(next);
}

Crps GrowingSurface::rest_crps() const {
    return Crps(with_positions(m_mesh, m_rest_positions), m_crps.topology());
}

std::vector<double> GrowingSurface::triangle_areas(double age) const {
    const TriangleMesh m = with_positions(m_mesh, m_shape.at(age));
    std::vector<double> out(m.num_triangles());
    for (TriId t = 0; t < out.size(); ++t) out[t] = m.triangle_area(t);
    return out;
}

void carry_cells(const Crps &from, const Crps &to, Cells &cells) {
    for (CellId c = 0; c < cells.size(); ++c) {
        const TriId t = cells.tri(c);
        cells.move(c, {t, to.barycentric_to_2d(t, from.to_barycentric(t, cells.pos(c)))});
    }
}

std::vector<double> growth_divisions(const Crps &crps, const Cells &cells,
                                     const CellTypes &types,
                                     const std::vector<double> &area_now,
                                     const std::vector<double> &area_next,
                                     double cell_area, double *lost,
                                     const std::vector<double> *cell_rates) {
    // g_i ∝ 1 / division_time_i (a type that never divides has g = 0); the normalisation
    // Σ g_i = 1 cancels in k.
    std::vector<double> g(types.size(), 0);
    for (int i = 0; i < types.size(); ++i)
        if (types[i].divides()) g[i] = 1 / types[i].division_time;
    auto rate = [&](CellId c) {
        return cell_rates ? (*cell_rates)[c] : g[cells.type(c)];
    };
    auto weight_on = [&](TriId t) {
        double w = 0;
        for (CellId c : cells.on(t)) w += rate(c);
        return w;
    };
    std::vector<double> expected(cells.size(), 0);
    double lost_cells = 0;
    const size_t nt = crps.num_triangles();
    for (TriId t = 0; t < nt; ++t) {
        const double dA = area_next[t] - area_now[t];
        if (!(dA > 0)) continue;  // shrinking or still: no division (thesis: no rule)
        const double dN = dA / cell_area;
        const double w = weight_on(t);
        if (w > 0) {
            const double k = dN / w;  // thesis L1490: k = ΔN / Σ N_i g_i
            for (CellId c : cells.on(t)) expected[c] += k * rate(c);
            continue;
        }
        const auto nbrs = crps.topology().neighbours(t);
        double wn = 0;
        for (TriId j : nbrs) wn += weight_on(j);
        if (!(wn > 0)) {
            lost_cells += dN;
            continue;
        }
        const double k = dN / wn;
        for (TriId j : nbrs)
            for (CellId c : cells.on(j)) expected[c] += k * rate(c);
    }
    if (lost) *lost = lost_cells;
    return expected;
}

}  // namespace pelage::sim
