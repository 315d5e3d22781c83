// The coat (coat.h) as an OpenUSD stage in the text format:
//   /coat                 Xform, the default prim
//     /<object>           Xform with the object's transform (xformOp:transform)
//       /skin             Mesh: points, faceVertexCounts/Indices, faceVarying normals and
//                         st, per face (uniform) displayColor, cell_type and cell_id;
//                         subdivisionScheme "none" (the triangles are the surface)
//       /pattern          Material (UsdPreviewSurface reading the baked texture through
//                         st), bound to the skin, when the skin has a texture
//       /fur              BasisCurves: cubic B-spline (round strands, Embree's
//                         ROUND_BSPLINE_CURVE with its phantom end points, so the curve
//                         starts at the root) or linear (flat ribbons); points, widths
//                         per vertex; per curve (uniform) displayColor, cell_type,
//                         cell_id, root_uv; and Unreal's groom attributes groom_color,
//                         groom_width, groom_root_uv, groom_id.
// Frames of an animation become time samples: an attribute whose value differs between
// frames is written as timeSamples at each frame's time code, one that does not as its
// single value.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "renderer/export/coat.h"

namespace pelage::renderer {

struct UsdStageInfo {
    char up_axis = 'Y';  // 'Y' or 'Z' (UsdGeom's upAxis)
    double meters_per_unit = 1;
    double fps = 24;            // timeCodesPerSecond
    std::vector<double> times;  // the time code of each frame; one frame: ignored
    std::string doc;            // the layer's doc string (what wrote it)
};

// Writes frames (one for a still; every frame with the same skins and grooms) to `out`.
// Throws std::invalid_argument when the frames do not match one another.
void write_coat_usda(std::ostream &out, const std::vector<CoatFrame> &frames,
                     const UsdStageInfo &info);

}  // namespace pelage::renderer
