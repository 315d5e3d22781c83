#include "renderer/image/cryptomatte_read.h"

#include <OpenImageIO/imageio.h>
#include <fnmatch.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "renderer/image/cryptomatte.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

std::unique_ptr<OIIO::ImageInput> open_exr(const std::string &path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path, 0, "", "cannot read the image: " + OIIO::geterror());
    return in;
}

std::vector<CryptomatteManifest> manifests_of(const OIIO::ImageSpec &spec,
                                              const std::string &path) {
    std::vector<CryptomatteManifest> out;
    for (const auto &a : spec.extra_attribs) {
        const std::string n = a.name().string();
        const std::string suffix = "/name";
        if (n.rfind("cryptomatte/", 0) != 0 || n.size() <= suffix.size() ||
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string prefix = n.substr(0, n.size() - suffix.size() + 1);
        CryptomatteManifest m;
        m.layer = a.get_string();
        const std::string text = spec.get_string_attribute(prefix + "manifest");
        const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
        if (!j.is_object())
            throw InputError(path, 0, prefix + "manifest", "is not a JSON object");
        for (const auto &[name, hex] : j.items()) {
            if (!hex.is_string())
                throw InputError(path, 0, prefix + "manifest",
                                 "\"" + name + "\" has no hex id");
            m.ids[name] = uint32_t(std::stoul(hex.get<std::string>(), nullptr, 16));
        }
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace

std::vector<CryptomatteManifest> read_cryptomatte_manifests(const std::string &path) {
    return manifests_of(open_exr(path)->spec(), path);
}

Matte read_cryptomatte_matte(const std::string &path, const std::string &layer,
                             const std::vector<std::string> &patterns) {
    auto in = open_exr(path);
    const OIIO::ImageSpec spec = in->spec();
    const std::string want =
        layer.rfind("Crypto", 0) == 0 ? layer : cryptomatte_layer_name(layer);
    const auto all = manifests_of(spec, path);
    const CryptomatteManifest *m = nullptr;
    std::string names;
    for (const auto &x : all) {
        if (x.layer == want) m = &x;
        names += (names.empty() ? "" : ", ") + x.layer;
    }
    if (!m)
        throw InputError(path, 0, "--layer",
                         "no Cryptomatte layer \"" + want + "\" (the file has " +
                             (names.empty() ? std::string("none") : names) + ")");
    Matte out;
    out.width = spec.width;
    out.height = spec.height;
    std::set<float> ids;
    for (const std::string &p : patterns) {
        bool any = false;
        for (const auto &[name, bits] : m->ids)
            if (fnmatch(p.c_str(), name.c_str(), 0) == 0) {
                ids.insert(cryptomatte_id(bits));
                out.names.push_back(name);
                any = true;
            }
        if (!any)
            throw InputError(path, 0, "--name",
                             "\"" + p + "\" matches no name in " + want + "'s manifest");
    }
    std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()))
        throw InputError(path, 0, "", "cannot read the pixels: " + in->geterror());
    out.alpha.assign(size_t(spec.width) * spec.height, 0.0f);
    for (int image = 0;; ++image) {
        char base[64];
        std::snprintf(base, sizeof base, "%s%02d.", want.c_str(), image);
        const int r = spec.channelindex(std::string(base) + "R");
        if (r < 0) break;
        const int ch[4] = {r, spec.channelindex(std::string(base) + "G"),
                           spec.channelindex(std::string(base) + "B"),
                           spec.channelindex(std::string(base) + "A")};
        for (size_t p = 0; p < out.alpha.size(); ++p) {
            const float *v = &px[p * spec.nchannels];
            for (int pair = 0; pair < 2; ++pair)
                if (ch[2 * pair] >= 0 && ch[2 * pair + 1] >= 0 &&
                    ids.count(v[ch[2 * pair]]))
                    out.alpha[p] += v[ch[2 * pair + 1]];
        }
    }
    return out;
}

}  // namespace pelage::renderer
