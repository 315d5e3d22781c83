// A skin's pattern baked into a texture for an export (pattern/bake): into the mesh's
// own UVs when they lie in one tile (0-1), else into an atlas of the surface, whose UVs
// the export then carries; written as an sRGB PNG (texture_png.h).
#pragma once

#include <string>
#include <vector>

#include "renderer/export/coat.h"
#include "renderer/scene/scene.h"

namespace pelage::renderer {

struct SkinTexture {
    std::vector<float> uvs;  // the UVs the texture is baked on, 6 per triangle
    std::string path;        // the PNG written
};

// Bakes `skin` (of `scene`) into a size × size PNG at `path`. Throws pelage::InputError
// at --texture when the object has no .cells file or the atlas cannot hold its charts.
SkinTexture bake_skin_texture(const Scene &scene, const CoatSkin &skin, int size,
                              const std::string &path);

}  // namespace pelage::renderer
