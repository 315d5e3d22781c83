// Rendering small scenes from JSON text inside a test, through the library.
#pragma once

#include <tbb/global_control.h>

#include <string>
#include <vector>

#include "renderer/integrator/render.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "tests/test_paths.h"

namespace pelage::test {

struct RenderedImage {
    int width = 0, height = 0;
    std::vector<float> pixels;  // Film::num_channels per pixel
    renderer::RenderStats stats;
    float at(int x, int y, int c) const {
        return pixels[(size_t(y) * width + x) * renderer::Film::num_channels + c];
    }
};

inline RenderedImage render_json(const std::string &json, const TempDir &dir,
                                 int threads = 0, uint64_t seed = 0) {
    const std::string path = dir.write("scene.json", json);
    const renderer::SceneDesc desc = renderer::load_scene_file(path);
    const renderer::PluginRegistry plugins;
    const renderer::Scene scene(desc, plugins);
    std::unique_ptr<tbb::global_control> c;
    if (threads > 0)
        c = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(threads));
    renderer::RenderOptions o;
    o.seed = seed;
    const renderer::RenderResult r = renderer::render(scene, o);
    return {desc.film.width, desc.film.height, r.film->resolve(), r.stats};
}

}  // namespace pelage::test
