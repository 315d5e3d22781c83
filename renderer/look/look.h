// From a mesh to a scene: what `pelage look` makes before it renders. The animal is
// chosen among the file's objects (look_objects.h), framed in a three-quarter view over
// every pose of a clip (renderer/camera/auto_frame.h), and given a preset's pattern, a
// ground, a sky and a sun (look_scene.h). The scene is complete: written beside the
// output, the user edits it and renders it again.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "renderer/look/look_scene.h"

namespace pelage::renderer {

struct LookRequest {
    std::string mesh;  // a file, FILE#NAME or procedural:...
    std::string preset = "giraffe-reticulata";
    std::string presets_dir;  // the shipped presets (a name is looked up there)
    std::string output;       // the EXR; "" = MESH_NAME.exr in the current folder
    int width = 960, height = 540, spp = 64;
    Vec3f up{0, 1, 0};
    std::string view = "Filmic";
    uint64_t seed = 1;
    bool fur = false;
    bool denoise = false;  // the scene's film.denoise
    // A clip of the mesh file: `frames` (a frame list, "" = the whole clip once) at
    // `fps`, blurred over `shutter` of each frame.
    std::string clip, frames;
    double fps = 24, shutter = 0;
};

struct LookPlan {
    LookSetup setup;
    std::filesystem::path scene_path;  // where the scene goes: beside the output
    std::string render_frames;         // the frame list to render ("" = the still)
};

// Checks the request (errors name the `pelage look` option: -o, --frames, --shutter,
// --clip) and makes the scene. `warn` hears what the user should know of the file's
// objects (which one the pattern grows on, a missing texture). Throws InputError.
LookPlan plan_look(const LookRequest &request,
                   const std::function<void(const std::string &)> &warn);

}  // namespace pelage::renderer
