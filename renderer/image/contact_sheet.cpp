#include "renderer/image/contact_sheet.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "renderer/image/image_output.h"

namespace pelage::renderer {

// DejaVu Sans from Debian's fonts-dejavu-core (installed by the quick start).
static const char *const label_font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

bool write_contact_sheet(const std::string &path, int width, int height,
                         const std::vector<SheetImage> &images,
                         const DisplayTransform &display) {
    const int gap = 8, label = 30, n = int(images.size());
    const int W = n * width + (n + 1) * gap, H = height + label + 2 * gap;
    std::vector<float> sheet(size_t(W) * H * 3, 0.02f);
    for (int i = 0; i < n; ++i) {
        const int x0 = gap + i * (width + gap), y0 = gap + label;
        for (int y = 0; y < height; ++y)
            std::copy_n(images[i].rgb->data() + size_t(y) * width * 3, size_t(width) * 3,
                        sheet.data() + (size_t(y0 + y) * W + x0) * 3);
    }
    bool labelled = true;
    {
        OIIO::ImageBuf buf(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::FLOAT), sheet.data());
        const float white[3] = {1, 1, 1};
        for (int i = 0; i < n; ++i)
            labelled &= OIIO::ImageBufAlgo::render_text(buf, gap + i * (width + gap) + 4,
                                                        gap + label - 8, images[i].label,
                                                        20, label_font, white);
    }
    write_preview(path, W, H, sheet, 3, display);
    return labelled;
}

}  // namespace pelage::renderer
