#include "apps/explore/preview_surface.h"

#include <cmath>

#include "sim/remesh/simplify.h"

namespace pelage::renderer::explore {

std::optional<sim::TriangleMesh> simplify_for_preview(const sim::TriangleMesh &input,
                                                      double divisor, double deviation) {
    if (input.num_triangles() < 2000 || input.num_triangles() > 200000) return {};
    sim::Bounds3 box;
    for (const sim::Vec3d &p : input.positions) box.extend(p);
    const double bound = deviation * box.diagonal();
    double edge = std::sqrt(divisor) * sim::mean_edge_length(input);
    for (int attempt = 0; attempt < 3; ++attempt, edge *= 0.5) {
        sim::TriangleMesh coarse = sim::simplify(input, {edge, bound});
        if (sim::max_vertex_distance(input, coarse) <= 1.5 * bound) return coarse;
    }
    return {};
}

}  // namespace pelage::renderer::explore
