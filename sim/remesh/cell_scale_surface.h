// The surface a simulation runs on: the input mesh when its triangles are at the cells'
// scale or it is light enough, else a copy simplified (simplify.h) or refined to it.
//
// The relaxation's neighbourhoods are built per triangle and reach R ≈ w_r·s (s the
// cell spacing, largest at the start), so their size grows as triangles × (R/e)² for
// mean edge e, while the pattern needs the surface only to the cells' scale. The input
// is simplified when both hold: its mean edge is shorter than the final cell spacing
// s = sqrt(A / m), and its neighbourhoods at the initial radius would hold more than
// max_neighbourhood_entries unfolded triangles, triangles × π(R + e)² / (√3/4·e²).
// Edges shorter than s are collapsed (about 2 triangles per cell where the shape
// allows), and no collapse may move a vertex farther than max_deviation_fraction of the
// bounding-box diagonal nor a tenth of s from the input, so the pattern transfers back
// to the input (pattern/transfer/surface_transfer.h) well inside its 2 % tolerance.
//
// The collapse threshold is the edge at which the estimate comes down to
// max_neighbourhood_entries, at least s (at most max_cells_per_triangle cells per
// triangle): at giraffe-reticulata's start R is about 15 s, and a copy at s itself kept
// ~1 800 unfolded triangles per triangle (the cow split 4 times: > 9 GB). A mesh whose
// triangles are already larger than s is coarsened the same way when its estimate is
// over coarsen_entries (camel: 5 cells per triangle, 4.9 M entries, 47 of its 55 s
// growing spent building neighbourhoods; bunny00: 35 M). Collapsing long edges can fold
// a thin part (a tail, a horn) into a stub whose vertices still lie on the input, so a
// copy is kept only when every vertex of the input lies within
// max_input_distance_fraction of the diagonal from it and the area changed by at most
// max_area_change; otherwise the threshold is halved, down to s (whose copy is kept, as
// it always was) or, when coarsening, to the input's mean edge (then the input is used).
//
// A mesh far finer than the collapse edge (a hero mesh: the cow split four times, 1.5 M
// triangles) is first reduced by a greedy collapse (greedy_collapse.h) to half the edge,
// which keeps every vertex on the input and the input's topology, or is not used; CGAL's
// collapse then starts from there, its bound still measured against the input.
//
// A mesh much coarser than the cells (a low-poly animal: the heffalump's elephant holds
// 900 cells per triangle, the spider's abdomen 3 500) is refined instead: the relaxation
// and division steps meet every cell of a triangle's unfolded neighbourhood, so their
// cost per cell grows with the cells per triangle. Each triangle is split in four at its
// edge midpoints (sim/mesh/subdivide.h) until at most max_cells_per_triangle cells are
// expected on one: the same surface exactly, so the transfer back is exact too.
#pragma once

#include <cstddef>
#include <string>

#include "sim/mesh/mesh.h"

namespace pelage::sim {

struct CellScaleRequest {
    double area = 0;                  // of the input
    double expected_cells = 0;        // at the end of the run
    double neighbourhood_radius = 0;  // R at the start of the run
};

struct CellScaleReport {
    bool simplified = false;  // planned, or done
    size_t input_triangles = 0, output_triangles = 0;
    double cell_spacing = 0;              // s = sqrt(A / expected final cells)
    double input_mean_edge = 0;           // of the input
    double neighbourhood_entries = 0;     // estimated for the input
    double edge_length = 0;               // collapse threshold (0 when not simplified)
    double min_edge_length = 0;           // lowest threshold tried
    bool coarsening = false;              // triangles larger than s (checked, may fail)
    double max_input_distance = 0;        // measured: input vertices to the result
    double max_deviation = 0;             // bound on the distance from the input
    double bbox_diagonal = 0;             // of the input
    size_t pre_collapsed_triangles = 0;   // after the greedy collapse (0: none)
    int refine_levels = 0;                // midpoint splits (0 when not refined)
    double input_cells_per_triangle = 0;  // expected at the end, on the input

    bool remeshed() const { return simplified || refine_levels > 0; }
};

inline constexpr double max_deviation_fraction = 0.002;
inline constexpr double max_neighbourhood_entries = 5e5;
inline constexpr double max_cells_per_triangle = 128;
inline constexpr double coarsen_entries = 4 * max_neighbourhood_entries;
inline constexpr double max_input_distance_fraction = 0.005;
inline constexpr double max_area_change = 0.02;
// A mesh whose mean edge is under half of this fraction of the collapse edge is first
// collapsed greedily to it.
inline constexpr double pre_collapse_fraction = 0.5;
// Its share of the distance the result may keep from the input.
inline constexpr double pre_collapse_distance = 0.25;

// Whether the mesh is to be simplified or refined, and how (output_triangles is the
// input's until remesh_to_cell_scale has run when simplifying): a cheap look at the
// mesh, so a caller can release what it built on a dense input before simplifying.
CellScaleReport plan_cell_scale(const TriangleMesh &mesh,
                                const CellScaleRequest &request);
// The mesh to simulate on: the input simplified or refined as planned, or unchanged.
TriangleMesh remesh_to_cell_scale(const TriangleMesh &mesh, CellScaleReport *plan);

// About what the relaxation's neighbourhoods of the planned surface take at the initial
// radius, in bytes (the unfolded triangles the plan estimates, at about 64 bytes each
// while they are built).
double neighbourhood_bytes(const CellScaleReport &plan);
// InputError (field simulation.initial_cells) naming the mesh, the memory the
// neighbourhoods would take and what to change, when that is more than `budget` bytes.
void check_neighbourhood_memory(const CellScaleReport &plan, double budget,
                                const std::string &mesh_path);

}  // namespace pelage::sim
