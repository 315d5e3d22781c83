#include "sim/remesh/cell_scale_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "sim/core/input_error.h"
#include "sim/mesh/subdivide.h"
#include "sim/remesh/greedy_collapse.h"
#include "sim/remesh/simplify.h"

namespace pelage::sim {

CellScaleReport plan_cell_scale(const TriangleMesh &mesh,
                                const CellScaleRequest &request) {
    CellScaleReport rep;
    rep.input_triangles = rep.output_triangles = mesh.num_triangles();
    rep.cell_spacing = std::sqrt(request.area / std::max(request.expected_cells, 1.0));
    rep.input_mean_edge = mean_edge_length(mesh);
    rep.bbox_diagonal = mesh.bounds().diagonal();
    const double e = rep.input_mean_edge, R = request.neighbourhood_radius;
    if (e > 0)
        rep.neighbourhood_entries = double(mesh.num_triangles()) * 3.141592653589793 *
                                    (R + e) * (R + e) / (0.4330127018922193 * e * e);
    const double s = rep.cell_spacing;
    rep.coarsening = e >= s && rep.neighbourhood_entries > coarsen_entries;
    rep.simplified =
        e > 0 && ((e < s && rep.neighbourhood_entries > max_neighbourhood_entries) ||
                  rep.coarsening);
    if (rep.simplified) {
        // The edge at which the estimate is max_neighbourhood_entries (it falls as the
        // edge grows), by bisection, at least s and at most max_cells_per_triangle cells
        // on a triangle of that edge: s alone (about two triangles per cell) left a
        // neighbourhood of ~1 800 triangles per triangle at giraffe-reticulata's start.
        const double longest = std::sqrt(max_cells_per_triangle / 0.4330127018922193) * s;
        auto entries = [&](double edge) {
            const double triangles = request.area / (0.4330127018922193 * edge * edge);
            return triangles * 3.141592653589793 * (R + edge) * (R + edge) /
                   (0.4330127018922193 * edge * edge);
        };
        double lo = std::min(e, s), hi = std::max({e, s, longest});
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (entries(mid) > max_neighbourhood_entries ? lo : hi) = mid;
        }
        rep.edge_length = std::max(hi, s);
        rep.min_edge_length = rep.coarsening ? e : s;
        rep.max_deviation =
            std::min(max_deviation_fraction * rep.bbox_diagonal, 0.1 * rep.cell_spacing);
    } else if (e > 0 && mesh.num_triangles() > 0) {
        double per_triangle = request.expected_cells / double(mesh.num_triangles());
        rep.input_cells_per_triangle = per_triangle;
        while (per_triangle > max_cells_per_triangle && rep.refine_levels < 8) {
            ++rep.refine_levels;
            per_triangle /= 4;
        }
        if (rep.refine_levels > 0) {
            const double split = std::ldexp(1.0, rep.refine_levels);  // edges / split
            rep.output_triangles = mesh.num_triangles() * size_t(split * split);
            const double er = e / split;
            rep.neighbourhood_entries = double(rep.output_triangles) * 3.141592653589793 *
                                        (R + er) * (R + er) /
                                        (0.4330127018922193 * er * er);
        }
    }
    return rep;
}

TriangleMesh remesh_to_cell_scale(const TriangleMesh &mesh, CellScaleReport *plan) {
    if (plan->refine_levels > 0) {
        TriangleMesh out = mesh;
        for (int level = 0; level < plan->refine_levels; ++level)
            out = subdivide(out, Subdivision::midpoint);
        plan->output_triangles = out.num_triangles();
        return out;
    }
    if (!plan->simplified) return mesh;
    const double area = mesh.surface_area();
    for (double edge = plan->edge_length;;
         edge = std::max(0.5 * edge, plan->min_edge_length)) {
        // A mesh far finer than the edge is reduced greedily first, to a fraction of it.
        const double first = pre_collapse_fraction * edge;
        std::optional<TriangleMesh> reduced;
        if (!plan->coarsening && 2 * plan->input_mean_edge < first)
            reduced = greedy_collapse(
                mesh, {first, pre_collapse_distance * max_input_distance_fraction *
                                  plan->bbox_diagonal});
        plan->pre_collapsed_triangles = reduced ? reduced->num_triangles() : 0;
        TriangleMesh out = reduced
                               ? simplify(*reduced, {edge, plan->max_deviation, &mesh})
                               : simplify(mesh, {edge, plan->max_deviation});
        plan->edge_length = edge;
        plan->output_triangles = out.num_triangles();
        plan->max_input_distance = max_vertex_distance(mesh, out);
        const bool close = plan->max_input_distance <=
                               max_input_distance_fraction * plan->bbox_diagonal &&
                           std::abs(out.surface_area() / area - 1) <= max_area_change;
        if (close) return out;
        // At the cells' own scale a finer input keeps its copy, as it always has.
        if (edge <= plan->min_edge_length && !plan->coarsening) return out;
        if (edge <= plan->min_edge_length) break;
    }
    // No coarser copy stays on the input: the input as it is.
    plan->simplified = plan->coarsening = false;
    plan->pre_collapsed_triangles = 0;
    plan->edge_length = plan->min_edge_length = 0;
    plan->output_triangles = plan->input_triangles;
    return mesh;
}

double neighbourhood_bytes(const CellScaleReport &plan) {
    // A simplified surface holds about max_neighbourhood_entries; the input or a refined
    // copy its estimate.
    const double entries =
        plan.simplified ? std::min(plan.neighbourhood_entries, max_neighbourhood_entries)
                        : plan.neighbourhood_entries;
    return 64.0 * entries;
}

void check_neighbourhood_memory(const CellScaleReport &plan, double budget,
                                const std::string &mesh_path) {
    const double need = neighbourhood_bytes(plan);
    if (need <= budget) return;
    char text[512];
    std::snprintf(
        text, sizeof text,
        "the relaxation would need about %.1f GB for the neighbourhoods of its "
        "%zu triangles (mean edge %.3g) at the initial repulsion radius, more than "
        "the %.1f GB available: start from more cells (--initial-cells, or "
        "simulation.initial_cells / initial_spacing), a smaller w_r, or a coarser "
        "mesh",
        need / 1e9, plan.input_triangles, plan.input_mean_edge, budget / 1e9);
    throw InputError(mesh_path, 0, "simulation.initial_cells", text);
}

}  // namespace pelage::sim
