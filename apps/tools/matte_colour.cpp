#include "apps/tools/matte_colour.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "renderer/image/cryptomatte.h"
#include "renderer/image/cryptomatte_read.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

// An EXR's RGB, row by row.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<Rgb> rgb;
};

RgbImage read_rgb(const std::string &exr) {
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
    RgbImage out{spec.width, spec.height, {}};
    out.rgb.resize(size_t(spec.width) * size_t(spec.height));
    for (size_t i = 0; i < out.rgb.size(); ++i) {
        const float *p = &px[i * size_t(spec.nchannels)];
        out.rgb[i] = {p[r], p[g], p[b]};
    }
    return out;
}

// The names of `layer` (its manifest), or an InputError naming `exr`.
std::vector<std::string> layer_names(const std::string &exr, const std::string &layer) {
    const std::string wanted = cryptomatte_layer_name(layer);
    std::vector<std::string> names;
    for (const CryptomatteManifest &m : read_cryptomatte_manifests(exr))
        if (m.layer == wanted || m.layer == layer)
            for (const auto &[name, id] : m.ids) names.push_back(name);
    if (names.empty())
        throw InputError(exr, 0, "", "no Cryptomatte layer \"" + layer + "\"");
    return names;
}

Rgb mean_over(const RgbImage &image, const std::vector<uint8_t> &mask, size_t pixels) {
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i])
            for (int k = 0; k < 3; ++k) sum[k] += image.rgb[i][k];
    if (pixels == 0) return {0, 0, 0};
    return {float(sum[0] / double(pixels)), float(sum[1] / double(pixels)),
            float(sum[2] / double(pixels))};
}

}  // namespace

std::vector<uint8_t> matte_interior(const Matte &m, float min_coverage, int erode) {
    const int w = m.width, h = m.height;
    std::vector<uint8_t> covered(m.alpha.size()), out(m.alpha.size(), 0);
    for (size_t i = 0; i < m.alpha.size(); ++i)
        covered[i] = m.alpha[i] >= min_coverage;  // false for NaN too
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool all = true;
            // Pixels beyond the frame count as uncovered: their light is unknown.
            for (int dy = -erode; dy <= erode && all; ++dy)
                for (int dx = -erode; dx <= erode && all; ++dx) {
                    const int u = x + dx, v = y + dy;
                    all = u >= 0 && v >= 0 && u < w && v < h &&
                          covered[size_t(v) * size_t(w) + size_t(u)];
                }
            out[size_t(y) * size_t(w) + size_t(x)] = all;
        }
    return out;
}

std::vector<MatteColour> mean_colour_by_matte(const std::string &exr,
                                              const std::string &layer,
                                              float min_coverage, int erode) {
    const RgbImage image = read_rgb(exr);
    std::vector<MatteColour> out;
    for (const std::string &name : layer_names(exr, layer)) {
        // A name holding '*' would match others: such names are measured as the set.
        const Matte matte = read_cryptomatte_matte(exr, layer, {name});
        const std::vector<uint8_t> mask = matte_interior(matte, min_coverage, erode);
        MatteColour c;
        c.name = name;
        c.pixels = size_t(std::count(mask.begin(), mask.end(), 1));
        c.mean = mean_over(image, mask, c.pixels);
        out.push_back(c);
    }
    return out;
}

std::vector<MatteColourPair> mean_colours_by_matte(const std::string &exr,
                                                   const std::string &other,
                                                   const std::string &layer,
                                                   float min_coverage, int erode) {
    const RgbImage a = read_rgb(exr), b = read_rgb(other);
    if (a.width != b.width || a.height != b.height)
        throw InputError(other, 0, "",
                         "is " + std::to_string(b.width) + "x" +
                             std::to_string(b.height) + ", not the " +
                             std::to_string(a.width) + "x" + std::to_string(a.height) +
                             " of " + exr);
    std::vector<MatteColourPair> out;
    for (const std::string &name : layer_names(exr, layer)) {
        const Matte matte = read_cryptomatte_matte(exr, layer, {name});
        const std::vector<uint8_t> mask = matte_interior(matte, min_coverage, erode);
        MatteColourPair c;
        c.name = name;
        c.pixels = size_t(std::count(mask.begin(), mask.end(), 1));
        c.mean = mean_over(a, mask, c.pixels);
        c.other_mean = mean_over(b, mask, c.pixels);
        out.push_back(c);
    }
    return out;
}

}  // namespace pelage::renderer
