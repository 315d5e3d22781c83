#include "pattern/mosaic/pattern.h"

#include "sim/mesh/mesh_clean.h"

namespace pelage::pattern::mosaic {
namespace {

// Whether `render` is the surface `grown` triangle by triangle: as many triangles, each
// corner within round-off of the other's, 1e-7 of the size (the distance under which
// the mesh loader welds vertices into one, sim/mesh/mesh_clean.h). How the corners
// share vertices may differ (the renderer unwelds the rest pose of a skinned file so
// that seams can move apart; a file may store each triangle's corners on their own),
// and the positions differ in their last bits (the .cells file keeps each triangle's
// frame, not its vertices): the pattern's triangle t is then the render's triangle t
// and its barycentric points are the same points, so no transfer is needed.
bool same_surface(const sim::TriangleMesh &render, const sim::TriangleMesh &grown) {
    if (render.num_triangles() != grown.num_triangles()) return false;
    const double tolerance =
        sim::MeshCleanOptions{}.weld_relative * grown.bounds().diagonal();
    for (sim::TriId t = 0; t < grown.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c)
            if (!(length(render.vertex(t, c) - grown.vertex(t, c)) <= tolerance))
                return false;
    return true;
}

}  // namespace

MosaicPattern::MosaicPattern(const std::string &cells_path, const std::string &mesh_path,
                             Neighbourhood neighbourhood)
    // The same loader as `pelage sim` and the renderer: for the mesh the cells were grown
    // on, identical triangles, so a hit's primitive id is the .cells triangle.
    : MosaicPattern(cells_path, sim::load_mesh(mesh_path), mesh_path, neighbourhood) {}

MosaicPattern::MosaicPattern(const std::string &cells_path, sim::TriangleMesh render,
                             const std::string &render_name, Neighbourhood neighbourhood)
    : m_data(sim::read_cells_file(cells_path)) {
    if (m_data.num_triangles() == render.num_triangles() &&
        m_data.mesh_hash == sim::mesh_hash(render)) {
        m_surface = std::make_unique<sim::Surface>(sim::build_surface(std::move(render)));
    } else {
        sim::TriangleMesh grown = sim::surface_mesh(m_data, cells_path);
        const bool same = same_surface(render, grown);
        m_surface = std::make_unique<sim::Surface>(sim::build_surface(std::move(grown)));
        if (!same)
            m_transfer = std::make_unique<transfer::SurfaceTransfer>(
                *m_surface, render, cells_path, render_name);
    }
    index_cells(neighbourhood);
}

MosaicPattern::MosaicPattern(const std::string &cells_path, Neighbourhood neighbourhood)
    : m_data(sim::read_cells_file(cells_path)) {
    m_surface = std::make_unique<sim::Surface>(
        sim::build_surface(sim::surface_mesh(m_data, cells_path)));
    index_cells(neighbourhood);
}

void MosaicPattern::index_cells(Neighbourhood neighbourhood) {
    std::vector<CellOnSurface> list;
    list.reserve(m_data.num_cells());
    for (sim::TriId t = 0; t < m_data.num_triangles(); ++t)
        for (uint32_t k = m_data.cell_row[t]; k < m_data.cell_row[t + 1]; ++k)
            list.push_back({t, m_data.x[k], m_data.z[k], m_data.id[k], m_data.type[k]});
    m_cells = make_cell_table(m_data.num_triangles(), list);
    m_index = std::make_unique<ClosestCellIndex>(m_surface->crps, m_cells,
                                                 ClosestCellOptions{neighbourhood});
    m_tri.resize(6 * m_data.num_triangles());
    for (sim::TriId t = 0; t < m_data.num_triangles(); ++t) {
        const sim::CrpsFrame &f = m_surface->crps.frame(t);
        const sim::Vec2d e1 = f.v[1] - f.v[0], e2 = f.v[2] - f.v[0];
        const float v[6] = {float(f.v[0].x), float(f.v[0].y), float(e1.x),
                            float(e1.y),     float(e2.x),     float(e2.y)};
        std::copy(v, v + 6, &m_tri[6 * t]);
    }
    std::vector<char> reaches(m_data.num_triangles());
    for (sim::TriId t = 0; t < m_data.num_triangles(); ++t)
        reaches[t] = m_index->reaches_cells(t);
    m_cover = std::make_unique<transfer::CellCover>(*m_surface, reaches);
}

}  // namespace pelage::pattern::mosaic
