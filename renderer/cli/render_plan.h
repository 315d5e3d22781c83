// What `pelage render` is asked to do: its options, and the plan checked from them
// before any work starts (outputs, frames, tile), with the command-line overrides
// applied to the scene.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "renderer/cli/common.h"
#include "renderer/cli/render_tiles.h"
#include "renderer/image/color_management.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer::cli {

// The options of `pelage render`, as given.
struct RenderCliOptions {
    std::string scene, output, preview, res, view;
    int spp = 0;
    double noise_threshold = -1;  // < 0: the scene's film.noise_threshold
    unsigned long long seed = 0;
    bool resume = false, cryptomatte = false;
    QuietOption quiet;
    StatsJsonOption stats_json;
    std::string frames, tile;
    int step = 1;
    ThreadOption threads;
};

// What the command line asks for, checked before any work starts.
struct RenderPlan {
    std::string output, preview;  // file names, with a frame token (####) for a range
    std::optional<DisplayTransform> display;
    bool animated = false;  // --frames given
    std::vector<int> frames;
    std::string settings;  // settings_hash() of the run; per frame, frame_settings_hash
    std::optional<TileSpec> tile;  // --tile: rows [tile_y0, tile_y1) of a still
    int tile_y0 = 0, tile_y1 = 0;
};

// Runs `pelage render` with these options; returns its exit code.
int run_render(const RenderCliOptions &o);

// Applies the command-line overrides to `desc`, then checks every output: a missing
// folder or a bad name fails now, not after the render. Throws pelage::InputError.
RenderPlan plan_render(const RenderCliOptions &o, SceneDesc &desc);

}  // namespace pelage::renderer::cli
