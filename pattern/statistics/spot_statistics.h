// Statistics of a pattern's look, measured on the surface as the renderer shows it: the
// spots (connected regions of every non-background cell), their areas, neighbours and
// shapes, and how the background is laid out between them.
//
// Method. Every triangle is covered by a barycentric grid fine against the cells (spacing
// sqrt(A/m) / resolution) and each grid vertex takes its nearest cell from the renderer's
// closest-cell search. Grid sub-triangles give each cell its area; grid edges whose ends
// fall in different cells give the cells' adjacency (the Voronoi neighbours). A spot's
// perimeter is its border traced through the grid: on every sub-triangle side whose ends
// lie in different spots the border's crossing is found on the bisector of the cells
// that meet there (a cell nearer the crossing than both ends' cells takes the place of
// its side's end, and the crossing is found again), and the crossings of each
// sub-triangle are joined by a chord. The chords follow the border to second order in the
// grid step whatever the triangles' shape: a disc, an ellipse or a spherical cap is
// measured within 1 % at resolution 6 (0.5 % once it is 30 cells across), on two
// triangles, on slivers 20 times longer than wide or on a sphere
// (tests/pattern/statistics/spot_perimeter_test.cpp). Counting
// crossings of the grid's three edge families (Cauchy-Crofton) instead is exact only for
// families evenly spread in direction: on a sliver triangle all three run nearly along
// it, borders along it go uncounted, and an ellipse's perimeter came out 19 % short.
//
// Derived measures:
//   * spot neighbours: every background cell joins its nearest spot in hops over the
//     adjacency (a multi-source breadth-first search); two spots are neighbours when
//     their regions touch. This is the spot-level tessellation whose mean side count
//     Dagg (1968) reports for giraffes (Walter thesis §3.5, Table 3.2).
//   * circularity 4 pi A / P^2 per spot (1 for a disc in the plane), and Miyazawa's
//     complexity 1 - (area-weighted mean circularity) (Miyazawa, "Pattern blending
//     enriches the diversity of animal colorations", Science Advances 2020). The ratio
//     is the plane's: the isoperimetric inequality P^2 >= 4 pi A that bounds it by 1
//     holds in the plane, not on a curved or closed surface. A spherical cap of angular
//     radius theta has 2 / (1 + cos theta) (1.06 at 0.5 rad, 4.9 at 2.2 rad); a spot
//     round a leg or tail (a band: area 2 pi r h, border two loops 4 pi r) has h / (2 r),
//     and one capping a horn, an ear or the muzzle above 1 too. Such spots are measured
//     right and still exceed 1, and the complexity can then be negative.
//   * the background's connectivity: its connected components, the area share of the
//     largest, and the share of its area in cells that touch a spot (1 for a thin
//     network between spots, small for spots on a wide background).
#pragma once

#include <cstddef>
#include <vector>

#include "pattern/mosaic/pattern.h"

namespace pelage::pattern::statistics {

struct SpotStatistics {
    double area = 0;              // the surface's area
    size_t grid_points = 0;       // closest-cell look-ups made
    std::vector<double> by_type;  // area fraction per type, indexed like the types
    size_t spots = 0;             // connected regions of non-background cells
    double spot_area_mean = 0;    // surface units
    double spot_area_sd = 0;      // population standard deviation
    double spot_neighbours_mean = 0;
    double spot_circularity_mean = 0;     // over spots with a border
    double spot_complexity = 0;           // 1 − area-weighted mean circularity
    std::vector<double> spot_areas;       // per spot, largest first
    std::vector<double> spot_perimeters;  // per spot, in the order of spot_areas
    size_t largest_spot_cells = 0;        // cells in the spot of most cells
    size_t background_components = 0;
    double background_largest_share = 0;  // of the background's area
    double background_near_spot = 0;      // share of background area touching a spot
};

// `resolution` is the number of grid steps per mean cell spacing sqrt(A/m) (>= 1); 6
// resolves cell borders to a sixth of a cell. Deterministic; the background is the type
// named "B" (else type 1); a mosaic of one type has no background and every cell is
// spot.
SpotStatistics measure_spot_statistics(const mosaic::MosaicPattern &pattern,
                                       double resolution = 6);

// The q-quantile (q in [0, 1]) of the spots' areas, linear between order statistics; 0
// when there is no spot.
double spot_area_quantile(const SpotStatistics &s, double q);

}  // namespace pelage::pattern::statistics
