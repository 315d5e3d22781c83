// A render job's plan: its outputs, frames and tile checked before any work starts, with
// the job's changes applied to the scene.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "renderer/image/color_management.h"
#include "renderer/job/render_job.h"
#include "renderer/job/render_tiles.h"

namespace pelage::renderer {

struct RenderPlan {
    std::string output, preview;  // file names, with a frame token (####) for a range
    std::optional<DisplayTransform> display;
    bool animated = false;  // a frame list given
    std::vector<int> frames;
    std::string settings;  // settings_hash() of the run; per frame, frame_settings_hash
    std::optional<TileSpec> tile;  // rows [tile_y0, tile_y1) of a still
    int tile_y0 = 0, tile_y1 = 0;
};

// Applies the job's changes to `desc`, then checks every output: a missing folder or a
// bad name fails now, not after the render. Throws pelage::InputError.
RenderPlan plan_render(const RenderJob &job, SceneDesc &desc);

}  // namespace pelage::renderer
