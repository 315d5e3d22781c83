// Rendering a scene: progressive passes of 1, 1, 2, 4, 8 ... samples over all pixels,
// each pass a TBB parallel loop over 16×16 tiles. Every pixel's samples are summed in
// sample order, and random numbers depend only on (seed, frame, x, y, sample), so the
// image is bit-identical at any thread count. A cancel request stops at the next tile;
// the film then holds all completed work (each pixel is normalized by its own weight
// sum).
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "renderer/image/film.h"
#include "renderer/integrator/integrator_path.h"
#include "renderer/scene/scene.h"

namespace pelage::renderer {

struct RenderOptions {
    uint64_t seed = 0;
    uint32_t frame = 0;
    const std::atomic<bool> *cancel = nullptr;
    // Draw a progress bar of pixel-samples (the caller checks for a TTY).
    bool progress = false;
    // Instrumentation (`pelage bench render`, `pelage render --stats-json`): when set,
    // the integrator's instrumented instantiation runs, timing 1 plugin call in
    // `plugin_timing_stride` (plugin_seconds) and, with record_rays, keeping every ray
    // cast. Unset, the production instantiation carries none of it (instrumentation.h).
    bool instrument = false;
    uint64_t plugin_timing_stride = 16;  // 1: every call
    bool record_rays = false;            // implies instrument
    // Animation: the camera to use instead of the scene's, and camera motion blur; both
    // optional.
    std::optional<CameraDesc> camera;
    std::optional<CameraMotion> camera_motion;
    // Only this part of the image, [x0, x1) × [y0, y1) (a tile of a still split over a
    // farm): its pixels come out exactly as in a whole render, since samples depend on
    // the pixel alone and camera packets on the tile grid's columns (so columns extend
    // to whole 16-pixel tiles). Adaptive sampling's decisions spread one pixel per
    // pass, so that many pixels around the region are rendered too, and with
    // film.denoise the denoiser's support radius more.
    struct Region {
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    };
    std::optional<Region> region;
};

struct RenderResult {
    std::unique_ptr<Film> film;
    RenderStats stats;
    // Samples of the last pass every (still sampling) pixel received: the spp asked
    // for, unless interrupted or, with adaptive sampling, every pixel converged sooner.
    int spp_done = 0;
    bool interrupted = false;
    double seconds = 0;
    // The progress bar's accounting, in pixel-samples: `work_total` is width × height ×
    // spp; `work_done` counts the samples taken plus, with adaptive sampling, the
    // samples a pixel no longer needs once it converges. Equal when complete.
    uint64_t work_done = 0, work_total = 0;
    // With a region: the samples its pixels took, and the spp_done a whole render would
    // report were the region the whole image (the last pass any of its pixels took).
    uint64_t region_samples = 0;
    int region_spp_done = 0;
    std::vector<std::vector<RecordedRay>> rays;  // per thread, when record_rays
};

RenderResult render(const Scene &scene, const RenderOptions &options);

}  // namespace pelage::renderer
