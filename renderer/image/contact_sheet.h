// A labelled contact sheet: images side by side with their names above, converted to the
// display through OpenColorIO and written as PNG/JPEG (atomically, like every output).
#pragma once

#include <string>
#include <vector>

#include "renderer/image/color_management.h"

namespace pelage::renderer {

struct SheetImage {
    std::string label;
    const std::vector<float> *rgb;  // linear RGB, width × height × 3
};

// Returns false when the label font could not be used (the sheet is written unlabelled).
bool write_contact_sheet(const std::string &path, int width, int height,
                         const std::vector<SheetImage> &images,
                         const DisplayTransform &display);

}  // namespace pelage::renderer
