#include "renderer/export/skin_texture.h"

#include <optional>
#include <stdexcept>

#include "pattern/bake/bake.h"
#include "renderer/export/texture_png.h"
#include "renderer/image/image_output.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

SkinTexture bake_skin_texture(const Scene &scene, const CoatSkin &skin, int size,
                              const std::string &path) {
    const ObjectDesc &od = scene.desc().objects[skin.object];
    if (od.cells.empty())
        throw InputError(scene.desc().path, 0, "--texture",
                         "object \"" + skin.name +
                             "\" has no .cells file: only a mosaic's pattern is baked");
    const MeshData &m = *scene.geometry().objects()[skin.object].mesh;
    sim::TriangleMesh rest;
    rest.positions.resize(m.rest->positions.size() / 3);
    for (size_t v = 0; v < rest.positions.size(); ++v)
        rest.positions[v] = {m.rest->positions[3 * v], m.rest->positions[3 * v + 1],
                             m.rest->positions[3 * v + 2]};
    rest.triangles.resize(m.num_triangles);
    for (size_t t = 0; t < m.num_triangles; ++t)
        for (int c = 0; c < 3; ++c)
            rest.triangles[t][size_t(c)] = m.triangles[3 * t + size_t(c)];
    const pattern::mosaic::MosaicPattern pattern(od.cells, rest, od.mesh);
    SkinTexture tex;
    std::vector<float> pixels;
    bool own_uvs = !skin.uvs.empty();
    std::vector<sim::Vec2d> uvs;
    if (own_uvs) {
        for (size_t i = 0; i + 1 < skin.uvs.size(); i += 2)
            uvs.push_back({skin.uvs[i], skin.uvs[i + 1]});
        try {
            own_uvs = pattern::bake::udim_tiles(rest, uvs) == std::vector<int>{1001};
        } catch (const std::invalid_argument &) {
            own_uvs = false;
        }
    }
    if (own_uvs) {
        pattern::bake::BakeLayout layout;
        layout.mesh = &rest;
        layout.corner_uvs = uvs;
        layout.transfer = pattern.transfer();
        layout.width = layout.height = size;
        pattern::bake::BakeResult r = pattern::bake::bake_layout(pattern, layout);
        pixels = std::move(r.tiles.at(0).pixels);
        tex.uvs = skin.uvs;
    } else {
        std::optional<sim::Surface> render;
        if (pattern.transfer()) render = sim::build_surface(rest);
        std::optional<pattern::bake::BakedAtlas> baked;
        try {
            baked = pattern::bake::bake_atlas(pattern, size, size, 4,
                                              render ? &*render : nullptr);
        } catch (const std::invalid_argument &e) {
            std::string why =
                e.what();  // names bake's --res: this command's is --texture
            if (const size_t at = why.find("; raise --res"); at != std::string::npos)
                why.erase(at);
            throw InputError("", 0, "--texture",
                             std::to_string(size) + ": " + why + "; raise --texture");
        }
        pattern::bake::BakedAtlas &a = *baked;
        if (a.atlas.num_charts == 0 || skin.num_triangles() != m.num_triangles)
            throw std::runtime_error("the atlas does not cover the skin");
        tex.uvs.resize(6 * skin.num_triangles());
        for (size_t t = 0; t < skin.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c) {
                const sim::Vec2d uv = a.atlas.uv(sim::TriId(t), c);
                tex.uvs[6 * t + 2 * size_t(c)] = float(uv.x);
                tex.uvs[6 * t + 2 * size_t(c) + 1] = float(uv.y);
            }
        pixels = std::move(a.image.tiles.at(0).pixels);
    }
    const std::vector<unsigned char> rgb = srgb_rgb8(
        pixels, pattern::bake::BakeResult::channels, size_t(size) * size_t(size));
    write_rgb8(path, size, size, rgb);
    tex.path = path;
    return tex;
}

}  // namespace pelage::renderer
