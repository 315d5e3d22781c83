/* texture: an image texture looked up by the mesh's UVs through OpenImageIO's
 * TextureSystem (MIP-mapped, filtered by the ray footprint): the texture-mapping baseline
 * of Teo 2006 Table 7.9. With `pelage bake` it renders a mosaic as an ordinary texture.
 *
 * Colour: the renderer works in scene-linear Rec.709, so an image in another colour
 * space is converted once, when the instance is created — by the `colorspace`
 * parameter, else by the file's `oiio:ColorSpace` metadata, else by its pixel type (8-
 * and 16-bit integers are sRGB, half and float linear). The conversion goes through
 * OpenImageIO's ColorConfig (the OCIO config named by $OCIO when set, else OIIO's
 * built-in sRGB, Rec709 and gamma spaces) into a tiled, MIP-mapped float copy in a
 * temporary folder (ImageBufAlgo::make_texture), removed with the instance.
 *
 * UDIM: `<UDIM>` in the file name stands for the tile number, 1001 + u tile + 10 v tile
 * (Mari's numbering, as Arnold, RenderMan and OpenImageIO read it); the tiles present
 * are used, and UVs in a missing tile shade black.
 *
 * The parameters are the table below (`pelage shaders texture` prints it); no AOVs. The
 * mesh needs UVs (an OBJ with `vt`, e.g. from `pelage bake --obj`).
 */
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shader/pelage_shader.h"
#include "shader/sdk/create_guard.h"
#include "shader/sdk/params.h"

namespace {

using namespace pelage::shader::sdk;

constexpr const char *udim_token = "<UDIM>";

struct Texture {
    std::shared_ptr<OIIO::TextureSystem> system;
    OIIO::ustring file;
    OIIO::TextureSystem::TextureHandle *handle = nullptr;
    OIIO::TextureOpt::Wrap wrap = OIIO::TextureOpt::WrapClamp;
    bool udim = false;
    float texels_per_unit = 0, inv_res = 0;
    std::filesystem::path converted;  // the folder of linear copies, or empty

    ~Texture() {
        if (converted.empty()) return;
        std::error_code ec;
        std::filesystem::remove_all(converted, ec);
    }
};

std::atomic<uint64_t> conversions{0};

const PelageParamSpec params[] = {
    {"file",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0,
     0,
     "image file, relative to the scene file; <UDIM> in the name reads UDIM tiles"},
    {"texels_per_unit",
     PELAGE_PARAM_FLOAT,
     {0, 0, 0},
     nullptr,
     0.0f,
     1e9f,
     "texels per object-space unit (filters by the ray footprint); 0 = bilinear"},
    {"colorspace",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0,
     0,
     "the image's colour space (e.g. \"sRGB\", \"linear\", an OCIO name); empty: the "
     "file's metadata, else sRGB for 8/16-bit and linear for float images"},
    {"wrap",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "clamp",
     0,
     0,
     "outside [0, 1]: \"clamp\" (edge texels), \"periodic\" (tile), \"mirror\" or "
     "\"black\"; within each tile for UDIM"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Names OpenImageIO and common OCIO configs give scene-linear Rec.709 (or raw data).
bool is_linear(const std::string &space) {
    const std::string s = lower(space);
    return s == "linear" || s == "scene_linear" || s == "lin_rec709" || s == "lin_srgb" ||
           s == "linear rec.709 (srgb)" || s == "raw" || s == "data";
}

// The colour space of one image: the parameter, else its metadata, else by pixel type.
std::string colour_space_of(const std::string &path, const std::string &param) {
    if (!param.empty()) return param;
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error(path + ": cannot read: " + OIIO::geterror());
    const OIIO::ImageSpec &spec = in->spec();
    const std::string meta = spec.get_string_attribute("oiio:ColorSpace");
    if (!meta.empty()) return meta;
    const OIIO::TypeDesc f = spec.format;
    return f == OIIO::TypeDesc::HALF || f == OIIO::TypeDesc::FLOAT ||
                   f == OIIO::TypeDesc::DOUBLE
               ? "linear"
               : "sRGB";
}

// A linear, tiled, MIP-mapped copy of `path` at `out`.
void convert_to_linear(const std::string &path, const std::string &space,
                       const std::string &out) {
    OIIO::ImageBuf in(path);
    if (!in.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error(path + ": cannot read: " + in.geterror());
    OIIO::ImageBuf linear;
    if (!OIIO::ImageBufAlgo::colorconvert(linear, in, space, "linear"))
        throw std::invalid_argument("colorspace: cannot convert " + path + " from \"" +
                                    space + "\" to linear: " + linear.geterror());
    OIIO::ImageSpec config;
    config.format = OIIO::TypeDesc::FLOAT;
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, linear, out,
                                          config))
        throw std::runtime_error(out + ": cannot write: " + OIIO::geterror());
}

std::unique_ptr<Texture> make(const PelageParamSet &ps) {
    const Params params_by_name(params, ps);
    const std::string file = params_by_name.get_string("file");
    if (file.empty()) throw std::invalid_argument("needs \"file\": the image to map");
    if (!ps.mesh.corner_uvs)
        throw std::invalid_argument(
            "the mesh has no UVs (an OBJ with vt lines is needed)");
    auto t = std::make_unique<Texture>();
    const std::string wrap = params_by_name.get_string("wrap");
    if (wrap == "clamp")
        t->wrap = OIIO::TextureOpt::WrapClamp;
    else if (wrap == "periodic")
        t->wrap = OIIO::TextureOpt::WrapPeriodic;
    else if (wrap == "mirror")
        t->wrap = OIIO::TextureOpt::WrapMirror;
    else if (wrap == "black")
        t->wrap = OIIO::TextureOpt::WrapBlack;
    else
        throw std::invalid_argument("wrap: \"" + wrap +
                                    "\" is none of \"clamp\", \"periodic\", \"mirror\", "
                                    "\"black\"");

    std::filesystem::path p(file);
    if (p.is_relative() && ps.scene_dir && *ps.scene_dir)
        p = std::filesystem::path(ps.scene_dir) / p;
    const std::string name = p.string();
    const size_t token = name.find(udim_token);
    t->udim = token != std::string::npos;
    // The files behind the name: the UDIM tiles present, or the one image.
    std::vector<std::pair<int, std::string>> files;
    if (t->udim) {
        for (int udim = 1001; udim <= 1100; ++udim) {
            std::string f = name;
            f.replace(token, std::string(udim_token).size(), std::to_string(udim));
            if (std::filesystem::exists(f)) files.emplace_back(udim, f);
        }
        if (files.empty())
            throw std::invalid_argument(name + ": no UDIM tile (1001 to 1100) exists");
    } else {
        if (!std::filesystem::exists(p))
            throw std::invalid_argument(name + ": no such image");
        files.emplace_back(0, name);
    }

    // Images not in scene-linear go through a linear copy.
    const std::string param_space = params_by_name.get_string("colorspace");
    std::vector<std::string> spaces;
    bool convert = false;
    for (const auto &f : files) {
        spaces.push_back(colour_space_of(f.second, param_space));
        convert = convert || !is_linear(spaces.back());
    }
    std::string lookup = name;
    if (convert) {
        t->converted = std::filesystem::temp_directory_path() /
                       ("pelage_texture_" + std::to_string(getpid()) + "_" +
                        std::to_string(++conversions));
        std::filesystem::create_directories(t->converted);
        const std::string stem = t->udim ? "tile.<UDIM>.exr" : "image.exr";
        lookup = (t->converted / stem).string();
        for (size_t k = 0; k < files.size(); ++k) {
            std::string out = lookup;
            if (t->udim)
                out.replace(out.find(udim_token), std::string(udim_token).size(),
                            std::to_string(files[k].first));
            convert_to_linear(files[k].second, spaces[k], out);
        }
    }

    // The process-wide shared texture system: thread-safe, one cache for every
    // instance. (A private one would have to go through TextureSystem::destroy, which
    // in OIIO 2.4 frees its object with the wrong sized delete: an ASan report.)
    // A file rewritten since the cache opened it is re-read (force = false leaves
    // unchanged files, and the handles other instances hold, alone).
    t->system = std::shared_ptr<OIIO::TextureSystem>(OIIO::TextureSystem::create(true),
                                                     [](OIIO::TextureSystem *) {});
    t->system->attribute("automip", 1);
    t->file = OIIO::ustring(lookup);
    if (t->udim) {
        for (const auto &f : files) {
            std::string tile = lookup;
            tile.replace(tile.find(udim_token), std::string(udim_token).size(),
                         std::to_string(f.first));
            t->system->invalidate(OIIO::ustring(tile), false);
        }
    } else {
        t->system->invalidate(t->file, false);
    }
    t->handle = t->system->get_texture_handle(t->file);
    // The resolution that texels_per_unit refers to: the first tile's.
    std::string first = lookup;
    if (t->udim)
        first.replace(first.find(udim_token), std::string(udim_token).size(),
                      std::to_string(files[0].first));
    const OIIO::ImageSpec *spec = t->system->imagespec(
        t->system->get_texture_handle(OIIO::ustring(first)), nullptr);
    if (!t->handle || !spec)
        throw std::runtime_error(name + ": cannot read: " + t->system->geterror());
    t->texels_per_unit = params_by_name.get_float("texels_per_unit");
    t->inv_res = 1.0f / float(std::max(spec->width, spec->height));
    return t;
}

void shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const Texture &t = *static_cast<const Texture *>(self);
    if (!hit->has_uv) return;
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = t.wrap;
    // Bilinear, not OIIO's default smart bicubic: the cubic B-spline it magnifies with
    // does not pass through the texels (a texel centre reads 1/6 of each neighbour), so
    // a baked cell edge would come out blurred.
    opt.interpmode = OIIO::TextureOpt::InterpBilinear;
    // The footprint in uv units: object units × texels per unit / resolution.
    const float d =
        t.texels_per_unit > 0 ? hit->footprint * t.texels_per_unit * t.inv_res : 0.0f;
    float rgb[3] = {0.5f, 0.5f, 0.5f};
    // OBJ's v runs bottom to top, images top to bottom: within each UDIM tile, so the
    // texture system still finds the tile from the integer parts.
    const float u = hit->uv[0], v = hit->uv[1];
    const float tile_v = t.udim ? std::floor(v) : 0.0f;
    const float s = u, tt = 2 * tile_v + 1 - v;
    if (!t.system->texture(t.handle, nullptr, opt, s, tt, d, 0, 0, d, 3, rgb))
        rgb[0] = rgb[1] = rgb[2] = 0;  // a missing UDIM tile
    for (int k = 0; k < 3; ++k) out->albedo[k] = rgb[k];
}

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "texture",
    "an image texture by UV through OpenImageIO's TextureSystem (baseline)",
    params,
    nullptr,
    guarded_create<make>,
    shade,
    destroy_instance<Texture>,
    nullptr,
    nullptr,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
