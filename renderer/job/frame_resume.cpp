#include "renderer/job/frame_resume.h"

#include "renderer/image/image_output.h"
#include "renderer/job/input_hash.h"

namespace pelage::renderer {

bool frame_is_done(const std::string &exr, const std::string &settings,
                   const RenderPlan &plan, std::string *why) {
    if (!exr_is_complete(exr, why)) return false;
    const std::string recorded = recorded_settings_hash(exr);
    const bool same_tile =
        !plan.tile || exr_string_attribute(exr, tile_attribute) == plan.tile->label();
    if (recorded == settings && same_tile) return true;
    *why = recorded.empty()       ? "complete but without pelage:settings_xxh3"
           : recorded != settings ? "rendered with other settings"
                                  : "another tile";
    return false;
}

}  // namespace pelage::renderer
