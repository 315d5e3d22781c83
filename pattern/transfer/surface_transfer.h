// Rendering a pattern on another mesh of the same shape than the one it was grown on: a
// light proxy for the simulation, a subdivided, remeshed, re-exported or rescaled hero
// mesh for the render. Every point of the render mesh is carried to the nearest point of
// the simulation surface, where the closest-cell search answers as usual.
//
// The render mesh is first brought to the simulation surface's place and size: when
// their bounding boxes differ by more than 2 % of the diagonal (in centre or size), by
// the similarity that maps one box onto the other; else as it is (subdivision and
// remeshing move a surface by less than that). Then each render vertex and triangle
// centroid finds its closest point on the simulation surface (a uniform grid of its
// triangles). A render triangle keeps the simulation triangles of its centroid and
// corners, each with the corners' barycentric coordinates in that triangle's plane, and
// a hit takes the first that holds it (the centroid's first). A render triangle may
// span many simulation triangles (a low-poly animal simulated on a refined copy,
// sim/remesh/cell_scale_surface.h): a hit that none of them holds walks from the one it
// falls most inside of across the edge it lies beyond, in that triangle's plane, until a
// triangle holds it (point location by walking). Where
// sheets of the surface touch or cross, the closest triangle facing like the render
// triangle wins. A render mesh whose vertices lie farther than 2 % of the size
// from the simulation surface is another shape: refused, naming both files.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/crps/surface.h"
#include "sim/mesh/closest_point.h"

namespace pelage::pattern::transfer {

class SurfaceTransfer {
  public:
    // `simulation` must outlive the transfer (its CRPS is walked on).
    SurfaceTransfer(const sim::Surface &simulation, const sim::TriangleMesh &render,
                    const std::string &cells_path, const std::string &render_path);

    struct Target {
        sim::TriId tri;
        float b1, b2;
    };
    // The simulation surface's triangle and barycentric coordinates for barycentric
    // point (b1, b2) of render triangle t.
    Target map(uint32_t t, float b1, float b2) const;
    // Render lengths times this are simulation lengths (ray footprints).
    float scale() const { return m_scale; }
    size_t num_render_triangles() const { return m_tris.size(); }
    // The largest distance of a render vertex from the simulation surface, relative to
    // the surface's bounding-box diagonal.
    double max_deviation() const { return m_max_deviation; }
    bool similarity_applied() const { return m_similarity; }

  private:
    struct Candidate {
        sim::TriId tri = sim::invalid_id;
        float b[3][2];  // the render corners' (b1, b2) in tri
    };
    struct RenderTriangle {
        std::array<Candidate, 4> c;
        uint32_t n = 0;
    };
    std::vector<RenderTriangle> m_tris;
    // Each render triangle's corners placed on the simulation surface's size, for walks.
    std::vector<std::array<sim::Vec3d, 3>> m_placed;
    const sim::Crps *m_crps = nullptr;
    float m_scale = 1;
    double m_max_deviation = 0;
    bool m_similarity = false;
};

}  // namespace pelage::pattern::transfer
