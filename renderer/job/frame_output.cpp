#include "renderer/job/frame_output.h"

#include <fmt/format.h>

#include <filesystem>

#include "renderer/camera/camera.h"
#include "renderer/image/image_layers.h"
#include "renderer/image/image_output.h"

namespace pelage::renderer {

namespace {

namespace fs = std::filesystem;

// The scene's Cryptomatte layers, named through the scene.
std::vector<CryptomatteSource> matte_sources(const Scene &scene) {
    std::vector<CryptomatteSource> sources;
    for (size_t l = 0; l < scene.matte_layers().size(); ++l)
        sources.push_back({scene.matte_layers()[l], [&scene, l](uint64_t key) {
                               return scene.matte_name(int(l), key);
                           }});
    return sources;
}

// What a compositor or a farm reads from the header besides the pixels: the camera,
// the compression, and the settings that made the image.
void describe_render(const SceneDesc &fd, ImageMetadata &meta) {
    const Camera camera(fd.camera, fd.film.width, fd.film.height);
    meta.world_to_camera = camera.world_to_camera();
    meta.world_to_ndc = camera.world_to_ndc();
    meta.compression = fd.film.compression;
    if (fd.animation.present && meta.fps <= 0) meta.fps = fd.animation.fps;
    const char *filters[] = {"box", "gaussian", "blackman_harris"};
    meta.strings.emplace_back(
        "pelage:filter",
        fmt::format("{} {:g}", filters[int(fd.film.filter)], fd.film.filter_radius));
    meta.strings.emplace_back("pelage:sampler",
                              fd.integrator.sampler == IntegratorDesc::SamplerKind::sobol
                                  ? "sobol"
                                  : "independent");
    const char *selection[] = {"auto", "all", "power", "uniform"};
    meta.strings.emplace_back("pelage:light_selection",
                              selection[int(fd.integrator.light_selection)]);
    meta.ints.emplace_back("pelage:max_depth", fd.integrator.max_depth);
    meta.ints.emplace_back("pelage:rr_depth", fd.integrator.rr_depth);
}

}  // namespace

void write_frame(const RenderResult &r, const Scene &scene, const SceneDesc &fd,
                 const SceneDesc &desc, const RenderPlan &plan, const FrameFiles &files,
                 uint64_t seed, const std::function<void(const std::string &)> &warn,
                 const std::vector<float> &denoised) {
    ImageLayers layers = image_layers(*r.film, fd.film, scene.shader_aov_names(),
                                      matte_sources(scene), warn, denoised);
    ImageMetadata meta;
    meta.scene = fs::absolute(desc.path).lexically_normal().string();
    meta.software = "pelage " PELAGE_VERSION;
    meta.spp = r.spp_done;
    meta.seed = seed;
    meta.render_seconds = r.seconds;
    meta.interrupted = r.interrupted;
    meta.view = fd.film.view;  // `pelage movie` displays the frames through it
    meta.settings_xxh3 = files.settings;
    meta.clamp_indirect = fd.integrator.clamp_indirect;
    // Only fur reads it (renderer/integrator/integrator_fur.cpp): a bare image is not
    // biased by it and does not say so.
    if (scene.fur()) meta.fur_bounce_roughness = fd.integrator.fur_bounce_roughness;
    if (fd.film.noise_threshold > 0) {
        meta.noise_threshold = fd.film.noise_threshold;
        meta.min_spp = fd.film.min_spp;
        meta.mean_spp =
            double(r.stats.samples) / (double(fd.film.width) * fd.film.height);
    }
    if (plan.animated) {
        meta.frame = files.frame;
        if (desc.animation.present) meta.fps = desc.animation.fps;
    }
    describe_render(fd, meta);
    // No render time in the file: a frame or still rendered again, on another machine
    // or as merged tiles, is the same file byte for byte (the time is in --stats-json).
    meta.record_time = false;
    if (plan.tile) {
        layers.pixels =
            tile_pixels(layers.pixels, fd.film.height, plan.tile_y0, plan.tile_y1);
        layers.height = plan.tile_y1 - plan.tile_y0;
        describe_tile(*plan.tile, fd.film.width, fd.film.height, plan.tile_y0,
                      plan.tile_y1, r.region_samples, r.region_spp_done, &meta);
    }
    write_exr(files.exr, layers, meta);
    if (plan.display)
        write_preview(files.preview, fd.film.width, fd.film.height, layers.pixels,
                      layers.channels(), *plan.display,
                      denoised.empty() ? 0 : denoised_channel);
}

}  // namespace pelage::renderer
