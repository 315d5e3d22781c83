#include "apps/tools/matte_colour.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "renderer/image/cryptomatte.h"
#include "renderer/image/cryptomatte_read.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

std::vector<MatteColour> mean_colour_by_matte(const std::string &exr,
                                              const std::string &layer,
                                              float min_coverage) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) throw InputError(exr, 0, "", "cannot read the image: " + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    const int r = spec.channelindex("R"), g = spec.channelindex("G"),
              b = spec.channelindex("B");
    if (r < 0 || g < 0 || b < 0) throw InputError(exr, 0, "", "no R, G, B channels");
    std::vector<float> px(size_t(spec.width) * size_t(spec.height) *
                          size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()))
        throw InputError(exr, 0, "", "cannot read the pixels: " + in->geterror());
    in->close();

    const std::string wanted = cryptomatte_layer_name(layer);
    std::vector<std::string> names;
    for (const CryptomatteManifest &m : read_cryptomatte_manifests(exr))
        if (m.layer == wanted || m.layer == layer)
            for (const auto &[name, id] : m.ids) names.push_back(name);
    std::vector<MatteColour> out;
    for (const std::string &name : names) {
        // A name holding '*' would match others: such names are measured as the set.
        const Matte matte = read_cryptomatte_matte(exr, layer, {name});
        MatteColour c;
        c.name = name;
        double sum[3] = {0, 0, 0};
        for (size_t i = 0; i < matte.alpha.size(); ++i) {
            if (!(matte.alpha[i] >= min_coverage)) continue;
            const float *p = &px[i * size_t(spec.nchannels)];
            sum[0] += p[r], sum[1] += p[g], sum[2] += p[b];
            ++c.pixels;
        }
        if (c.pixels > 0)
            c.mean = {float(sum[0] / double(c.pixels)), float(sum[1] / double(c.pixels)),
                      float(sum[2] / double(c.pixels))};
        out.push_back(c);
    }
    if (names.empty())
        throw InputError(exr, 0, "", "no Cryptomatte layer \"" + layer + "\"");
    return out;
}

}  // namespace pelage::renderer
