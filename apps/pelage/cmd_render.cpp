// `pelage render SCENE.json`: render a scene file to a multi-layer EXR (and optionally a
// display-referred PNG/JPEG preview through OpenColorIO).
#include <memory>
#include <string>

#include "apps/common/common.h"
#include "apps/pelage/job_report.h"
#include "renderer/core/setup_phase.h"

namespace pelage::renderer::cli {
namespace {

// The options of `pelage render`, as given.
struct RenderCliOptions {
    std::string scene, output, preview, res, view;
    int spp = 0;
    double noise_threshold = -1;  // < 0: the scene's film.noise_threshold
    bool denoise = false;
    unsigned long long seed = 0;
    bool resume = false, cryptomatte = false;
    QuietOption quiet;
    StatsJsonOption stats_json;
    std::string frames, tile;
    int step = 1;
    ThreadOption threads;
};

int run(const RenderCliOptions &o) {
    const auto control = o.threads.apply();
    SetupPhase::show("render", o.quiet.progress());
    RenderJob job = render_job_from_file(o.scene);
    job.output = o.output;
    job.preview = o.preview;
    job.view = o.view;
    if (!o.res.empty()) parse_resolution(o.res, 65536, &job.width, &job.height);
    job.spp = o.spp;
    job.noise_threshold = o.noise_threshold;
    job.cryptomatte = o.cryptomatte;
    job.denoise = o.denoise;
    job.seed = o.seed;
    job.frames = o.frames;
    job.step = o.step;
    job.tile = o.tile;
    job.resume = o.resume;
    JobReporting reporting;
    reporting.quiet = o.quiet;
    reporting.stats_json = o.stats_json;
    reporting.threads = o.threads.threads;
    return run_reported(std::move(job), reporting);
}

}  // namespace

Runner add_render_command(CLI::App &app) {
    auto o = std::make_shared<RenderCliOptions>();
    CLI::App *sub =
        app.add_subcommand("render", "Render a scene file to a multi-layer EXR");
    sub->add_option("scene", o->scene, "Scene file (JSON; docs/guide/scene-format.md)")
        ->required();
    sub->add_option("-o,--output", o->output,
                    "Output EXR (default: the scene's film.output)");
    sub->add_option("--spp", o->spp, "Samples per pixel (overrides film.spp)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--noise-threshold", o->noise_threshold,
                    "Adaptive sampling: a pixel stops once its noise is below this "
                    "(0.01 clean, 0.1 preview; 0 = off; overrides "
                    "film.noise_threshold); --spp is then the most a pixel takes")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--res", o->res,
                    "Resolution WIDTHxHEIGHT (overrides film.width/height)");
    sub->add_option(
        "--sampler-seed", o->seed,
        "Seed of the sampler; the same seed gives the same image at any thread count "
        "(a pattern's seed is the scene's pattern.seed)");
    refuse_pattern_seed(*sub, "--sampler-seed");
    sub->add_option("--preview", o->preview,
                    "Also write a PNG/JPEG preview through OpenColorIO");
    sub->add_option("--view", o->view,
                    "OpenColorIO view of the preview (default: film.view, \"Standard\")");
    o->stats_json.add_to(*sub, "timing and ray counts");
    sub->add_flag("--cryptomatte", o->cryptomatte,
                  "Write every Cryptomatte layer the materials offer (film.cryptomatte)");
    sub->add_flag("--denoise", o->denoise,
                  "Denoise the beauty (film.denoise): the EXR adds the layer "
                  "denoised.R/G/B beside the noisy R G B A, and the preview shows it");
    sub->add_option("--frames", o->frames,
                    "Frames: 1001-1120, 1,5,9, 1-100x5 (every 5th), 0-20x5,33; -o then "
                    "names a sequence, out.####.exr, out.%04d.exr or out.$F4.exr");
    sub->add_option("--step", o->step,
                    "Every N-th frame of each --frames range without its own xSTEP")
        ->check(CLI::Range(1, 1000000));
    sub->add_option("--tile", o->tile,
                    "Render tile I of N (1-based) of a still, rows (I-1)*H/N to I*H/N-1, "
                    "into -o; `pelage merge` joins the tiles");
    sub->add_flag("--resume", o->resume,
                  "Skip frames whose EXR is complete (header and pixel checksum) and "
                  "was rendered with the same settings (pelage:settings_xxh3)");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
