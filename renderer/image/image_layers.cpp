#include "renderer/image/image_layers.h"

#include <stdexcept>

#include "renderer/image/cryptomatte.h"

namespace pelage::renderer {

ImageLayers image_layers(const Film &film, const FilmDesc &desc,
                         const std::vector<std::string> &shader_aov_names,
                         const std::vector<CryptomatteSource> &cryptomatte,
                         const std::function<void(const std::string &)> &warn,
                         const std::vector<float> &denoised) {
    using LT = FilmDesc::LayerType;
    const int W = film.width(), H = film.height();
    ImageLayers out;
    out.width = W;
    out.height = H;
    // The film's channels (Film::channel_names order) that are written, and as what.
    const std::vector<std::string> all = Film::channel_names(shader_aov_names);
    std::vector<int> pick;
    auto take = [&](int first, int count, LT type) {
        if (type == LT::off) return;
        for (int c = first; c < first + count; ++c) {
            pick.push_back(c);
            out.names.push_back(all[size_t(c)]);
            out.half.push_back(type == LT::half);
        }
    };
    take(0, 4, desc.half ? LT::half : LT::single);  // R G B A
    // The denoised beauty: a layer of its own, as V-Ray's and Cycles' denoisers keep the
    // noisy image beside the clean one, in the beauty's pixel type. Its channels are
    // not the film's (pick holds -1 for them).
    const bool has_denoised = !denoised.empty();
    if (has_denoised)
        for (const char *c : {"denoised.R", "denoised.G", "denoised.B"}) {
            pick.push_back(-1);
            out.names.push_back(c);
            out.half.push_back(desc.half);
        }
    take(4, 3, desc.albedo);
    take(7, 3, desc.normal);
    take(10, 1, desc.depth);
    take(11, 2, desc.id);
    // Only the slots a plugin names: an unnamed slot holds nothing.
    for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && size_t(k) < shader_aov_names.size();
         ++k)
        if (!shader_aov_names[size_t(k)].empty()) take(13 + k, 1, desc.shader);

    std::vector<CryptomatteLayer> mattes;
    if (const CryptomatteFilm *cf = film.cryptomatte())
        for (int l = 0; l < cf->layers() && size_t(l) < cryptomatte.size(); ++l) {
            const std::string name = cryptomatte_layer_name(cryptomatte[size_t(l)].matte);
            mattes.push_back(resolve_cryptomatte(
                *cf, l, name, desc.cryptomatte_ranks, W, H,
                [&](int x, int y) { return film.weight(x, y); },
                cryptomatte[size_t(l)].name_of, warn));
            if (mattes.back().manifest == "{}")
                warn("Cryptomatte " + name +
                     " is empty: no visible surface has an id in " +
                     "it (clones need .cells files from this version of pelage sim)");
            const std::string prefix = "cryptomatte/" + cryptomatte_key(name) + "/";
            out.attributes.emplace_back(prefix + "name", name);
            out.attributes.emplace_back(prefix + "hash", "MurmurHash3_32");
            out.attributes.emplace_back(prefix + "conversion", "uint32_to_float32");
            out.attributes.emplace_back(prefix + "manifest", mattes.back().manifest);
            for (const std::string &c : mattes.back().channels) {
                out.names.push_back(c);
                out.half.push_back(0);  // ids are bit patterns: float only
            }
        }

    if (has_denoised && denoised.size() != size_t(W) * H * 3)
        throw std::logic_error("image_layers: the denoised image is not the film's size");
    const std::vector<float> resolved = film.resolve();
    const int nc = out.channels();
    out.pixels.resize(size_t(W) * H * nc);
    for (size_t p = 0; p < size_t(W) * H; ++p) {
        float *o = &out.pixels[p * nc];
        const float *r = &resolved[p * Film::num_channels];
        size_t c = 0, d = 0;
        for (const int src : pick) o[c++] = src >= 0 ? r[src] : denoised[3 * p + d++];
        for (const CryptomatteLayer &m : mattes)
            for (const std::vector<float> &plane : m.planes) o[c++] = plane[p];
    }
    return out;
}

}  // namespace pelage::renderer
