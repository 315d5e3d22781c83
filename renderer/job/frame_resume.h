// --resume: whether a frame's EXR on disk already is the frame this run would write.
#pragma once

#include <string>

#include "renderer/job/render_plan.h"

namespace pelage::renderer {

// True when `exr` is complete (its header and pixel checksum hold) and was rendered
// with `settings` (pelage:settings_xxh3) and, for a tile, as the same tile: a complete
// frame of another resolution, spp or scene would make a mixed sequence. Otherwise
// `*why` says what is wrong with it ("no file" when there is none).
bool frame_is_done(const std::string &exr, const std::string &settings,
                   const RenderPlan &plan, std::string *why);

}  // namespace pelage::renderer
