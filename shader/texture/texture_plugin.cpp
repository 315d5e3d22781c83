/* texture: an image texture looked up by the mesh's UVs through OpenImageIO's
 * TextureSystem (MIP-mapped, filtered by the ray footprint): the texture-mapping baseline
 * of Teo 2006 Table 7.9. With `pelage bake` it renders a mosaic as an ordinary texture.
 *
 * The parameters are the table below (`pelage shaders texture` prints it); no AOVs. The
 * mesh needs UVs (an OBJ with `vt`, e.g. from `pelage bake --obj`).
 */
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "shader/pelage_shader.h"
#include "shader/sdk/create_guard.h"
#include "shader/sdk/params.h"

namespace {

using namespace pelage::shader::sdk;

struct Texture {
    std::shared_ptr<OIIO::TextureSystem> system;
    OIIO::ustring file;
    OIIO::TextureSystem::TextureHandle *handle = nullptr;
    float texels_per_unit = 0, inv_res = 0;
};

const PelageParamSpec params[] = {
    {"file",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0,
     0,
     "image file, relative to the scene file"},
    {"texels_per_unit",
     PELAGE_PARAM_FLOAT,
     {0, 0, 0},
     nullptr,
     0.0f,
     1e9f,
     "texels per object-space unit (filters by the ray footprint); 0 = bilinear"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

std::unique_ptr<Texture> make(const PelageParamSet &ps) {
    const Params params_by_name(params, ps);
    const std::string file = params_by_name.get_string("file");
    if (file.empty()) throw std::invalid_argument("needs \"file\": the image to map");
    if (!ps.mesh.corner_uvs)
        throw std::invalid_argument(
            "the mesh has no UVs (an OBJ with vt lines is needed)");
    std::filesystem::path p(file);
    if (p.is_relative() && ps.scene_dir && *ps.scene_dir)
        p = std::filesystem::path(ps.scene_dir) / p;
    if (!std::filesystem::exists(p))
        throw std::invalid_argument(p.string() + ": no such image");
    auto t = std::make_unique<Texture>();
    // The process-wide shared texture system: thread-safe, one cache for every
    // instance. (A private one would have to go through TextureSystem::destroy, which
    // in OIIO 2.4 frees its object with the wrong sized delete: an ASan report.)
    // A file rewritten since the cache opened it is re-read (force = false leaves
    // unchanged files, and the handles other instances hold, alone).
    t->system = std::shared_ptr<OIIO::TextureSystem>(OIIO::TextureSystem::create(true),
                                                     [](OIIO::TextureSystem *) {});
    t->system->attribute("automip", 1);
    t->file = OIIO::ustring(p.string());
    t->system->invalidate(t->file, false);
    t->handle = t->system->get_texture_handle(t->file);
    const OIIO::ImageSpec *spec =
        t->handle ? t->system->imagespec(t->handle, nullptr) : nullptr;
    if (!spec)
        throw std::runtime_error(p.string() + ": cannot read: " + t->system->geterror());
    t->texels_per_unit = params_by_name.get_float("texels_per_unit");
    t->inv_res = 1.0f / float(std::max(spec->width, spec->height));
    return t;
}

void shade(const void *self, const PelageHit *hit, PelageShade *out) {
    const Texture &t = *static_cast<const Texture *>(self);
    if (!hit->has_uv) return;
    OIIO::TextureOpt opt;
    opt.swrap = opt.twrap = OIIO::TextureOpt::WrapClamp;
    // The footprint in uv units: object units × texels per unit / resolution.
    const float d =
        t.texels_per_unit > 0 ? hit->footprint * t.texels_per_unit * t.inv_res : 0.0f;
    float rgb[3] = {0.5f, 0.5f, 0.5f};
    // OBJ's v runs bottom to top, images top to bottom.
    t.system->texture(t.handle, nullptr, opt, hit->uv[0], 1.0f - hit->uv[1], d, 0, 0, d,
                      3, rgb);
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
