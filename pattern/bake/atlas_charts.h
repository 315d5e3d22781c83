// The charts of the CRPS atlas (atlas.h): edge-connected triangles unfolded flat at
// their reference shapes, grown nearest candidate first from the largest free triangle,
// each turned to its least-area bounding box.
#pragma once

#include <array>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::pattern::bake {

struct Chart {
    std::vector<sim::TriId> tris;
    std::vector<std::array<sim::Vec2d, 3>> pos;  // chart coordinates, box corner at 0
    double w = 0, h = 0, area = 0;               // bounding box and triangle area
};

// Every triangle in exactly one chart; a triangle joins a chart when its unfolded copy
// overlaps none of the chart's and its normal is within `max_angle_deg` of the seed's.
std::vector<Chart> grow_charts(const sim::Crps &crps, double max_angle_deg);

// Turns a chart to its least-area bounding box (one side along a convex-hull edge,
// Freeman & Shapira 1975), lying flat (w >= h), with the box's corner at the origin.
void orient_chart(Chart &c);

}  // namespace pelage::pattern::bake
