// `pelage export`'s work, as a library call: a scene's coat, at a still or at every
// frame of its animation, written as an OpenUSD stage (usd_export.h), with the pattern
// baked into a texture per skin when asked. The scene is prepared as a render prepares
// it (missing patterns grown, each frame posed by renderer/scene_frame, fur grown by the
// Scene), so the exported coat is the rendered one.
//
// Outputs are written atomically (textures first, the stage last); on a failure none of
// them is left behind.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct ExportJob {
    SceneDesc scene;
    std::string output;                // .usda
    std::string output_flag = "-o";    // names it in errors
    std::vector<std::string> objects;  // by name; empty: every patterned object
    bool fur = true;
    // "" exports the animation's frames when anything but the camera moves, else a
    // still; otherwise a frame list (frame_list.h).
    std::string frames;
    int texture_size = 0;  // > 0: bake each skin's pattern into a texture this wide
    double meters_per_unit = 1;
    // The most control points the export may hold (every frame's strands), so a groom
    // that does not fit in memory fails at once with what to change.
    uint64_t max_points = 400'000'000;
    std::string command;  // what wrote it, for the stage's doc string
};

struct ExportReport {
    std::vector<int> frames;  // the frame numbers exported (one for a still)
    size_t skins = 0, triangles = 0, strands = 0, points = 0;  // per frame
    std::vector<std::string> files;  // the stage, then the textures
    uint64_t bytes = 0;              // of the stage
    double setup_seconds = 0;        // scenes, patterns and fur
    double texture_seconds = 0;      // baking the textures (pattern/bake)
    double write_seconds = 0;        // gathering the coat and writing the stage
};

// Throws pelage::InputError when job.output cannot be the stage (not .usda, no such
// folder): what run_export checks first, for a caller to check before other work.
void check_export_output(const ExportJob &job);

// Throws pelage::InputError for bad input (unknown objects, no pattern, a frame list
// outside the animation, a path that cannot be written, too large a groom).
ExportReport run_export(const ExportJob &job,
                        const std::function<void(const std::string &)> &note = {});

}  // namespace pelage::renderer
