#include "renderer/integrator/render.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "renderer/core/progress.h"

namespace pelage::renderer {

namespace {
constexpr int tile_size = 16;
}  // namespace

RenderResult render(const Scene &scene, const RenderOptions &opt) {
    const auto t0 = std::chrono::steady_clock::now();
    const FilmDesc &fd = scene.desc().film;
    const int W = fd.width, H = fd.height, spp = fd.spp;
    const Camera camera(opt.camera ? *opt.camera : scene.desc().camera, W, H);
    const PixelFilter filter(fd.filter, fd.filter_radius);
    PathIntegrator integrator(scene, camera, filter, W, H);
    if (opt.camera_motion) integrator.set_camera_motion(&*opt.camera_motion);
    const bool instrumented = opt.instrument || opt.record_rays;
    const double timer_overhead = instrumented ? timer_overhead_seconds() : 0.0;

    RenderResult result;
    // Cryptomatte keeps two ids per pixel more than it writes ranks. A sample whose id
    // finds every slot taken is not counted, so only pixels that see more ids than
    // that lose part of a matte.
    result.film = std::make_unique<Film>(W, H, int(scene.matte_layers().size()),
                                         fd.cryptomatte_ranks + 2, fd.denoise);
    // Passes of 1, 1, 2, 4, 8 ... samples: an early stop still has a whole image.
    std::vector<int> bounds = {0};
    while (bounds.back() < spp)
        bounds.push_back(std::min(spp, std::max(1, 2 * bounds.back())));
    const int passes = int(bounds.size()) - 1;
    const bool adaptive = fd.noise_threshold > 0;
    // The pixels rendered, [rx0, rx1) × [ry0, ry1): all, or the region and `margin`
    // pixels around it, in the tiles [tx0, tx1) × [ty0, ty1) of the grid. Columns
    // extend to whole tiles, since a camera packet is a run of a tile's row and must
    // hold the pixels it holds in a whole render; rows need no rounding.
    const RenderOptions::Region region =
        opt.region ? *opt.region : RenderOptions::Region{0, 0, W, H};
    // The denoiser reads its support around every pixel of the region, and those pixels
    // must be as in a whole render.
    const int margin =
        opt.region ? (adaptive ? passes : 0) +
                         (fd.denoise ? denoise_support_radius(DenoiseOptions{}) : 0)
                   : 0;
    const int ry0 = std::max(0, region.y0 - margin),
              ry1 = std::min(H, region.y1 + margin);
    const int tx0 = std::max(0, region.x0 - margin) / tile_size,
              tx1 = (std::min(W, region.x1 + margin) + tile_size - 1) / tile_size,
              ty0 = ry0 / tile_size, ty1 = (ry1 + tile_size - 1) / tile_size;
    const int num_tiles = (tx1 - tx0) * (ty1 - ty0);
    const int rx0 = tx0 * tile_size, rx1 = std::min(W, tx1 * tile_size);

    tbb::enumerable_thread_specific<RenderStats> stats;
    tbb::enumerable_thread_specific<std::vector<RecordedRay>> logs;
    // Progress in pixel-samples, not passes: passes double in size, so a count of
    // passes would show 50 % after an eighth of the work.
    const uint64_t rendered_pixels = uint64_t(rx1 - rx0) * uint64_t(ry1 - ry0);
    Progress progress("render", rendered_pixels * uint64_t(std::max(spp, 0)),
                      opt.progress);
    std::atomic<bool> stopped{false};

    // Adaptive sampling: after each pass from min_spp on, pixels whose noise is below the
    // threshold stop, unless a neighbour goes on (a one-pixel dilation, so a noisy
    // pixel's surroundings keep converging with it). The decision depends on the film
    // alone, so it is the same at any thread count. Pixels outside the tiles rendered
    // count as converged; the margin keeps that guess from reaching the region.
    std::vector<uint8_t> active, noisy;
    if (adaptive) active.assign(size_t(W) * H, 1);
    uint64_t num_active = rendered_pixels;
    auto update_active = [&] {
        noisy.assign(size_t(W) * H, 0);
        tbb::parallel_for(ry0, ry1, [&](int y) {
            for (int x = rx0; x < rx1; ++x)
                noisy[size_t(y) * W + x] = active[size_t(y) * W + x] &&
                                           result.film->noise(x, y) > fd.noise_threshold;
        });
        size_t n = 0;
        for (int y = ry0; y < ry1; ++y)
            for (int x = rx0; x < rx1; ++x) {
                bool on = false;
                for (int dy = -1; dy <= 1 && !on; ++dy)
                    for (int dx = -1; dx <= 1 && !on; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        on = xx >= 0 && yy >= 0 && xx < W && yy < H &&
                             noisy[size_t(yy) * W + xx];
                    }
                active[size_t(y) * W + x] = on;
                n += on;
            }
        return n;
    };

    // The region's pixels still sampling in the coming pass.
    auto region_active = [&] {
        if (!adaptive) return uint64_t(region.x1 - region.x0) * (region.y1 - region.y0);
        uint64_t n = 0;
        for (int y = region.y0; y < region.y1; ++y)
            for (int x = region.x0; x < region.x1; ++x) n += active[size_t(y) * W + x];
        return n;
    };
    for (int pass = 0; pass < passes && !stopped.load(); ++pass) {
        const int s0 = bounds[pass], s1 = bounds[pass + 1];
        if (adaptive && s0 >= std::min(fd.min_spp, spp)) {
            // A pixel that stops has its remaining budget done: the total stays the
            // budget, so the ETA is for the pixels still sampling.
            const uint64_t now_active = update_active();
            progress.advance((num_active - now_active) * uint64_t(spp - s0));
            num_active = now_active;
            if (num_active == 0) break;
        }
        const uint64_t in_region = opt.region ? region_active() : 0;
        tbb::parallel_for(
            tbb::blocked_range<int>(0, num_tiles, 1),
            [&](const tbb::blocked_range<int> &range) {
                RenderStats &st = stats.local();
                Sampler sampler(opt.seed, opt.frame,
                                scene.desc().integrator.sampler ==
                                        IntegratorDesc::SamplerKind::independent
                                    ? Sampler::Kind::independent
                                    : Sampler::Kind::sobol);
                auto render_tiles = [&](const auto &instr) {
                    for (int tile = range.begin(); tile != range.end(); ++tile) {
                        if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) {
                            stopped.store(true);
                            return;
                        }
                        const int tx = tx0 + tile % (tx1 - tx0),
                                  ty = ty0 + tile / (tx1 - tx0);
                        const int x0 = tx * tile_size, y0 = ty * tile_size;
                        const uint64_t samples_before = st.samples;
                        integrator.render_tile(
                            *result.film, sampler, x0, std::max(ry0, y0),
                            std::min(W, x0 + tile_size), std::min(ry1, y0 + tile_size),
                            s0, s1, st, instr, adaptive ? active.data() : nullptr);
                        progress.advance(st.samples - samples_before);
                    }
                };
                if (instrumented)
                    render_tiles(Instrumented{
                        opt.record_rays ? &logs.local() : nullptr,
                        std::max<uint64_t>(1, opt.plugin_timing_stride), timer_overhead});
                else
                    render_tiles(NoInstrumentation{});
            });
        scene.geometry().check();  // an Embree error fails the run
        if (!stopped.load()) result.spp_done = adaptive ? std::min(s1, fd.spp) : s1;
        if (!stopped.load() && in_region > 0) {
            result.region_samples += in_region * uint64_t(s1 - s0);
            result.region_spp_done = result.spp_done;
        }
    }
    progress.finish();
    result.work_done = progress.done();
    result.work_total = progress.total();
    result.interrupted = stopped.load();
    for (const RenderStats &s : stats) result.stats.add(s);
    if (opt.record_rays)
        for (auto &l : logs) result.rays.push_back(std::move(l));
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace pelage::renderer
