// A rendered frame to its files: the film resolved into image layers (with the
// Cryptomatte names), the metadata a compositor or a farm reads from the header, then the
// EXR (a tile's rows only) and the display-referred preview, each written atomically.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "renderer/integrator/render.h"
#include "renderer/job/render_plan.h"

namespace pelage::renderer {

struct FrameFiles {
    std::string exr, preview;  // the frame's names ("" preview: none)
    std::string settings;      // frame_settings_hash: pelage:settings_xxh3
    int frame = 0;             // the frame's number, recorded when the plan is animated
};

// Writes `r`, frame `files.frame` of `desc` (the frame's scene) rendered from `scene`.
// `warn` hears what the layers could not keep (a Cryptomatte name clash). `denoised`:
// the denoised beauty (RGB interleaved, the whole film), written as its own layer and
// shown by the preview; or empty.
void write_frame(const RenderResult &r, const Scene &scene, const SceneDesc &desc,
                 const SceneDesc &animation_desc, const RenderPlan &plan,
                 const FrameFiles &files, uint64_t seed,
                 const std::function<void(const std::string &)> &warn,
                 const std::vector<float> &denoised = {});

}  // namespace pelage::renderer
