// `pelage bench noise`: what a clean image costs. Renders a scene at several sample
// counts and seeds and measures each image against a converged reference of the same
// scene rendered by this build (apps/tools/noise_metrics.h): MSE and RMSE over the
// objects' pixels, fireflies, wall and CPU seconds, and time × MSE — for an unbiased
// renderer MSE falls as 1/time, so time × MSE is the cost of a given noise level and
// comparable across sample counts, settings and renderers (lower is better).
//
// The reference (by default 4096 spp, seed 999 983, which no run uses) is the scene
// without its biased approximations (integrator.clamp_indirect and
// integrator.fur_bounce_roughness set to 0), so a run's mean_rgb against it is the bias
// those settings cost; it is cached under
// --cache, keyed by the scene file, the files it reads (input_hash.h: meshes, cells
// files, environment images, files named in material parameters), the resolution, the
// reference's spp and seed, and this executable and its plugins: another build or
// another input renders a new one. --reference names the
// file instead, for comparing builds whose converged images agree (an unbiased sampling
// change).
//
// Prints one JSON object: {scene, width, height, reference: {spp, seed, seconds,
// cached, file}, object_pixels, reference_mean, runs: [{spp, seed, seconds,
// cpu_seconds, mse, rmse, relative_rmse, time_mse, fireflies, median_max,
// max_error_over_mean}], by_spp: [{spp, seconds, cpu_seconds, mse, rmse, time_mse,
// fireflies, max_error_over_mean (the largest over the seeds), mean_rgb}] (means over the
// seeds), reference_mean_rgb} (an output contract). mean_rgb against reference_mean_rgb
// (the same pixels) is a converged run's bias against another build's or setting's
// --reference.
//
// With --denoise, every run is also denoised (renderer/denoise) and measured the same
// way: each run gains `denoised: {seconds, mse, rmse, fireflies, mean_rgb, mse_ratio}`
// and each by_spp entry `denoised: {seconds, mse, mse_ratio, time_mse}` — mse_ratio is
// the noisy MSE over the denoised one, the denoiser's gain; time_mse counts the render
// and the denoise. On a pattern with a cell_type AOV (the clonal_mosaic shader) they also
// gain `type_edges: {halo_pixels, max_bias, types: [{type, bias, interior_pixels,
// error_by_distance}]}` (apps/tools/type_edge_metrics.h), the noisy image's beside it
// as `noisy_type_edges`, with the types of a 1-spp render's sample 0.
//
// Flicker: with 2 seeds or more, each by_spp entry (and its `denoised`) has `flicker`,
// the variance of a pixel across the seeds, averaged over the objects' pixels and the
// R, G, B channels. Frames of a still differ only in their random numbers (the sampler
// is seeded by seed and frame), so this is the frame-to-frame variance a turntable's
// static pixels show.

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/bench/bench.h"
#include "apps/tools/noise_metrics.h"
#include "apps/tools/type_edge_metrics.h"
#include "renderer/core/install_layout.h"
#include "renderer/denoise/denoise.h"
#include "renderer/integrator/render.h"
#include "renderer/job/input_hash.h"
#include "renderer/job/scene_patterns.h"
#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;
using namespace pelage::renderer;

struct BenchNoiseOptions {
    std::string scene, res = "640x360", cache, reference;
    std::vector<int> spp{16, 64, 256};
    int seeds = 2, reference_spp = 4096;
    bool denoise = false;
    uint64_t reference_seed = 999983;
    ThreadOption threads;
    BenchOutput out;
};

// Four channels per pixel (R, G, B, coverage) are all the metrics need.
constexpr int stride = 4;
constexpr char cache_magic[8] = {'P', 'L', 'N', 'O', 'I', 'S', 'E', '1'};

std::string default_cache_dir() {
    if (const char *x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return std::string(x) + "/pelage/noise";
    if (const char *h = std::getenv("HOME"); h && *h)
        return std::string(h) + "/.cache/pelage/noise";
    return (fs::temp_directory_path() / "pelage-noise").string();
}

std::string reference_key(const BenchNoiseOptions &o, const SceneDesc &desc,
                          const PluginRegistry &plugins) {
    ContentHash h;
    h.add_file(desc.path);
    for (const std::string &f : scene_input_files(desc)) h.add_file(f);
    // The renderer's code: bin/pelage is only a launcher.
    if (const std::string code = renderer::code_file(); !code.empty()) h.add_file(code);
    for (const auto &[name, plugin] : plugins.plugins()) h.add_file(plugin.file);
    h.add(std::to_string(desc.film.width) + "x" + std::to_string(desc.film.height) + " " +
          std::to_string(o.reference_spp) + " " + std::to_string(o.reference_seed) +
          " unbiased");
    return h.hex();
}

// RGB and coverage of a film, `stride` floats per pixel.
std::vector<float> rgba(const Film &film) {
    const std::vector<float> all = film.resolve();
    const size_t n = size_t(film.width()) * film.height();
    std::vector<float> out(n * stride);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < stride; ++c)
            out[i * stride + c] = all[i * Film::num_channels + c];
    return out;
}

bool read_reference(const std::string &path, int width, int height,
                    std::vector<float> *out) {
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    int32_t wh[2];
    if (!in.read(magic, 8) || std::memcmp(magic, cache_magic, 8) != 0 ||
        !in.read(reinterpret_cast<char *>(wh), sizeof(wh)) || wh[0] != width ||
        wh[1] != height)
        return false;
    out->resize(size_t(width) * height * stride);
    return bool(in.read(reinterpret_cast<char *>(out->data()),
                        std::streamsize(out->size() * sizeof(float))));
}

void write_reference(const std::string &path, int width, int height,
                     const std::vector<float> &pixels) {
    fs::create_directories(fs::path(path).parent_path());
    write_file_atomically(path, [&](std::ostream &out) {
        const int32_t wh[2] = {width, height};
        out.write(cache_magic, 8);
        out.write(reinterpret_cast<const char *>(wh), sizeof(wh));
        out.write(reinterpret_cast<const char *>(pixels.data()),
                  std::streamsize(pixels.size() * sizeof(float)));
    });
}

struct TimedRender {
    std::vector<float> pixels;
    double seconds = 0, cpu_seconds = 0;
    // With film.denoise: the denoised image (`stride` floats per pixel, the noisy
    // coverage) and the denoiser's wall and CPU seconds.
    std::vector<float> denoised;
    double denoise_seconds = 0, denoise_cpu_seconds = 0;
};

TimedRender timed_render(const Scene &scene, uint64_t seed) {
    RenderOptions ro;
    ro.seed = seed;
    const double cpu0 = process_cpu_seconds();
    const RenderResult r = render(scene, ro);
    const double cpu = process_cpu_seconds() - cpu0;
    TimedRender out;
    out.pixels = rgba(*r.film);
    out.seconds = r.seconds;
    out.cpu_seconds = cpu;
    if (r.film->has_halves()) {
        const Timer t;
        const double dcpu0 = process_cpu_seconds();
        const std::vector<float> rgb = denoise(r.film->resolve_halves());
        out.denoise_cpu_seconds = process_cpu_seconds() - dcpu0;
        out.denoise_seconds = t.seconds();
        out.denoised = out.pixels;
        for (size_t i = 0; i < rgb.size() / 3; ++i)
            for (int c = 0; c < 3; ++c) out.denoised[i * stride + c] = rgb[3 * i + c];
    }
    return out;
}

int run(const BenchNoiseOptions &o) {
    SceneDesc desc = load_scene_file(o.scene);
    grow_scene_patterns(desc, false);
    if (desc.animation.present)
        throw InputError(o.scene, 0, "animation",
                         "bench noise measures a still; remove the animation block");
    if (!o.res.empty())
        parse_resolution(o.res, 16384, &desc.film.width, &desc.film.height);
    const auto tbb_threads = o.threads.apply();
    const PluginRegistry plugins;
    const std::string cache_dir = o.cache.empty() ? default_cache_dir() : o.cache;
    const std::string ref_file =
        !o.reference.empty()
            ? o.reference
            : cache_dir + "/" + reference_key(o, desc, plugins) + ".noise-ref";

    // --- The reference: cached, or rendered once, without the biased settings ---
    SceneDesc ref_desc = desc;
    ref_desc.film.spp = o.reference_spp;
    ref_desc.film.denoise = false;
    ref_desc.integrator.clamp_indirect = 0;
    ref_desc.integrator.fur_bounce_roughness = 0;
    const Timer t_setup;
    std::unique_ptr<Scene> scene = std::make_unique<Scene>(ref_desc, plugins);
    const double setup_seconds = t_setup.seconds();
    std::vector<float> reference;
    double ref_seconds = 0;
    const bool cached =
        read_reference(ref_file, desc.film.width, desc.film.height, &reference);
    if (!cached) {
        if (!o.out.quiet)
            std::cerr << "pelage bench noise: rendering the " << o.reference_spp
                      << "-spp reference (cached as " << ref_file << ")\n";
        TimedRender ref = timed_render(*scene, o.reference_seed);
        ref_seconds = ref.seconds;
        reference = std::move(ref.pixels);
        write_reference(ref_file, desc.film.width, desc.film.height, reference);
    }

    // --- The cell types per pixel, for the edges' metrics ---
    std::vector<float> types;
    const std::vector<std::string> &aov_names = scene->shader_aov_names();
    if (o.denoise)
        for (size_t k = 0; k < aov_names.size(); ++k)
            if (aov_names[k] == "cell_type") {
                desc.film.spp = 1;
                const Scene one(desc, plugins);
                RenderOptions ro;
                ro.seed = o.reference_seed;
                const std::vector<float> all = render(one, ro).film->resolve();
                types.resize(all.size() / Film::num_channels);
                for (size_t i = 0; i < types.size(); ++i)
                    types[i] = all[i * Film::num_channels + Film::num_channels -
                                   PELAGE_SHADER_AOV_SLOTS + k];
            }
    auto edges_json = [&](const std::vector<float> &image) {
        const TypeEdgeMetrics e = measure_type_edges(
            image, reference, types, desc.film.width, desc.film.height, stride);
        nlohmann::json ts = nlohmann::json::array();
        for (const TypeEdgeMetrics::Type &t : e.types)
            ts.push_back({{"type", t.type},
                          {"bias", t.bias},
                          {"interior_pixels", t.interior_pixels},
                          {"error_by_distance", t.error_by_distance},
                          {"pixels_by_distance", t.pixels_by_distance}});
        return nlohmann::json{
            {"halo_pixels", e.halo_pixels}, {"max_bias", e.max_bias}, {"types", ts}};
    };

    // --- The runs, every sample count with every seed ---
    nlohmann::json runs = nlohmann::json::array(), by_spp = nlohmann::json::array();
    size_t object_pixels = 0;
    double reference_mean = 0;
    nlohmann::json reference_mean_rgb;
    auto rgb = [](const double *c) { return nlohmann::json{c[0], c[1], c[2]}; };
    for (int spp : o.spp) {
        desc.film.spp = spp;
        desc.film.denoise = o.denoise;
        scene = std::make_unique<Scene>(desc, plugins);
        double sum[8] = {};   // seconds, cpu, mse, rmse, fireflies, mean R, G, B
        double dsum[3] = {};  // denoised: seconds, cpu seconds, mse
        double worst = 0;     // max_error_over_mean over the seeds
        std::vector<std::vector<float>> images, denoised_images;
        for (int s = 1; s <= o.seeds; ++s) {
            const TimedRender r = timed_render(*scene, uint64_t(s));
            images.push_back(r.pixels);
            if (o.denoise) denoised_images.push_back(r.denoised);
            const NoiseMetrics m = measure_noise(r.pixels, reference, desc.film.width,
                                                 desc.film.height, stride);
            object_pixels = m.pixels;
            worst = std::max(worst, m.max_error_over_mean());
            reference_mean = m.reference_mean;
            reference_mean_rgb = rgb(m.reference_mean_rgb);
            runs.push_back({{"spp", spp},
                            {"seed", s},
                            {"seconds", r.seconds},
                            {"cpu_seconds", r.cpu_seconds},
                            {"mse", m.mse},
                            {"rmse", m.rmse},
                            {"relative_rmse", m.rmse / std::max(m.reference_mean, 1e-30)},
                            {"time_mse", r.cpu_seconds * m.mse},
                            {"fireflies", m.fireflies},
                            {"median_max", m.median_max},
                            {"max_error_over_mean", m.max_error_over_mean()},
                            {"mean_rgb", rgb(m.mean_rgb)}});
            if (o.denoise) {
                const NoiseMetrics d = measure_noise(
                    r.denoised, reference, desc.film.width, desc.film.height, stride);
                runs.back()["denoised"] = {{"seconds", r.denoise_seconds},
                                           {"cpu_seconds", r.denoise_cpu_seconds},
                                           {"mse", d.mse},
                                           {"rmse", d.rmse},
                                           {"fireflies", d.fireflies},
                                           {"mean_rgb", rgb(d.mean_rgb)},
                                           {"mse_ratio", m.mse / std::max(d.mse, 1e-30)}};
                if (!types.empty()) {
                    runs.back()["denoised"]["type_edges"] = edges_json(r.denoised);
                    runs.back()["noisy_type_edges"] = edges_json(r.pixels);
                }
                dsum[0] += r.denoise_seconds / o.seeds;
                dsum[1] += r.denoise_cpu_seconds / o.seeds;
                dsum[2] += d.mse / o.seeds;
            }
            const double v[8] = {r.seconds,     r.cpu_seconds,       m.mse,
                                 m.rmse,        double(m.fireflies), m.mean_rgb[0],
                                 m.mean_rgb[1], m.mean_rgb[2]};
            for (int k = 0; k < 8; ++k) sum[k] += v[k] / o.seeds;
        }
        // The variance across the seeds, pixel by pixel, over the objects' pixels.
        auto flicker = [&](const std::vector<std::vector<float>> &imgs) {
            double total = 0;
            size_t count = 0;
            for (size_t i = 0; i < reference.size() / stride; ++i) {
                if (reference[i * stride + 3] < 0.5f) continue;
                for (int c = 0; c < 3; ++c) {
                    double m = 0, m2 = 0;
                    for (const auto &img : imgs) {
                        m += img[i * stride + c];
                        m2 += double(img[i * stride + c]) * img[i * stride + c];
                    }
                    const double k = double(imgs.size());
                    total += std::max(0.0, (m2 - m * m / k) / (k - 1));
                    ++count;
                }
            }
            return count ? total / double(count) : 0.0;
        };
        by_spp.push_back({{"spp", spp},
                          {"seconds", sum[0]},
                          {"cpu_seconds", sum[1]},
                          {"mse", sum[2]},
                          {"rmse", sum[3]},
                          {"time_mse", sum[1] * sum[2]},
                          {"fireflies", sum[4]},
                          {"max_error_over_mean", worst},
                          {"mean_rgb", rgb(sum + 5)}});
        if (o.seeds >= 2) by_spp.back()["flicker"] = flicker(images);
        if (o.denoise)
            by_spp.back()["denoised"] = {{"seconds", dsum[0]},
                                         {"cpu_seconds", dsum[1]},
                                         {"mse", dsum[2]},
                                         {"mse_ratio", sum[2] / std::max(dsum[2], 1e-30)},
                                         {"time_mse", (sum[1] + dsum[1]) * dsum[2]}};
        if (o.denoise && o.seeds >= 2)
            by_spp.back()["denoised"]["flicker"] = flicker(denoised_images);
    }
    const nlohmann::json j = {{"scene", o.scene},
                              {"width", desc.film.width},
                              {"height", desc.film.height},
                              {"setup_seconds", setup_seconds},
                              {"reference",
                               {{"spp", o.reference_spp},
                                {"seed", o.reference_seed},
                                {"seconds", ref_seconds},
                                {"cached", cached},
                                {"file", ref_file}}},
                              {"object_pixels", object_pixels},
                              {"reference_mean", reference_mean},
                              {"reference_mean_rgb", reference_mean_rgb},
                              {"runs", runs},
                              {"by_spp", by_spp}};
    o.out.emit(j);
    return 0;
}

}  // namespace

Runner add_bench_noise(CLI::App &bench) {
    auto o = std::make_shared<BenchNoiseOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "noise",
        "Noise against a converged reference: MSE, fireflies, time x MSE per spp (JSON)");
    cmd->add_option("scene", o->scene, "Scene file (a still)")->required();
    cmd->add_option("--res", o->res, "Resolution WxH (\"\": the scene's)")
        ->capture_default_str();
    cmd->add_option("--spp", o->spp, "Sample counts to measure")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    cmd->add_option("--seeds", o->seeds, "Seeds per sample count (1, 2, ...)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--reference-spp", o->reference_spp, "Samples of the reference")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    cmd->add_option("--cache", o->cache,
                    "Folder of cached references (default: $XDG_CACHE_HOME/pelage/noise "
                    "or ~/.cache/pelage/noise)");
    cmd->add_option("--reference", o->reference,
                    "This reference file instead of the cache (rendered and written when "
                    "missing): to compare builds whose converged images agree");
    cmd->add_flag("--denoise", o->denoise,
                  "Also denoise every run and measure the denoised image");
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
