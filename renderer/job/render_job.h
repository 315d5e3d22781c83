// A render job: a scene description in memory with what a run changes of it (outputs,
// resolution, samples, frames, a tile, resume), run frame by frame. Running it checks
// every output before any work, grows missing patterns, renders each frame, writes its
// EXR (with the metadata a compositor or a farm reads) and its preview, and returns the
// totals. `pelage render`, `pelage look` and `pelage explore` are thin tools over it, as
// pbrt-v4's command line is over RenderCPU: no scene goes to disk in order to be
// rendered, and no command calls another.
#pragma once

#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "renderer/integrator/instrumentation.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct RenderJob {
    SceneDesc scene;
    // The scene as its JSON text: the settings hash (pelage:settings_xxh3) reads it, so
    // a scene made in memory hashes as the same scene written to a file.
    std::string scene_text;

    // What the run changes of the scene's film; unset values keep the scene's. The
    // error messages name them after the `pelage render` options they come from.
    std::string output, preview;  // -o, --preview
    std::string view;             // --view
    int width = 0, height = 0;    // --res (0: film.width/height)
    int spp = 0;                  // --spp
    double noise_threshold = -1;  // --noise-threshold (< 0: the film's)
    bool denoise = false;         // --denoise: film.denoise on
    bool cryptomatte = false;     // --cryptomatte: every layer the materials offer
    uint64_t seed = 0;

    // "" renders the still (the animation's first frame); else a frame list
    // (frame_list.h) with `step` for its ranges that give none (--frames, --step).
    std::string frames;
    int step = 1;
    std::string tile;     // "I/N": band I of N of a still (render_tiles.h)
    bool resume = false;  // skip frames already complete with the same settings

    // Further files the caller writes after the run (--stats-json): their folders are
    // checked with the outputs, before any work. (flag, path) pairs.
    std::vector<std::pair<std::string, std::string>> other_outputs;

    // How it runs: a progress bar (the caller checks for a terminal), plugin timing
    // for the statistics, and a flag that stops it at the next tile. With
    // `ctrl_c_stops`, Ctrl-C sets such a flag from the first frame on (InterruptGuard);
    // during the set-up before it, Ctrl-C still ends the process at once.
    bool progress = false;
    bool instrument = false;
    const std::atomic<bool> *cancel = nullptr;
    bool ctrl_c_stops = false;
};

// A job of the scene file `path`. Throws pelage::InputError.
RenderJob render_job_from_file(const std::string &path);
// A job of a scene given as JSON text; `path` names it in errors and anchors its
// relative paths (the file need not exist).
RenderJob render_job_from_text(const std::string &text, const std::string &path);

// One frame written, as the command reports it.
struct FrameReport {
    int frame = 0;
    std::string output;
    int width = 0, height = 0;
    std::string tile;  // "I/N", or ""
    int spp = 0;       // samples every pixel received
    double mean_spp = 0;
    bool adaptive = false;
    double seconds = 0, rays_per_second = 0;
    uint64_t nonfinite_samples = 0;
};

// What a run tells as it goes: `info` is a command's normal output (a frame skipped or
// rendered again), `note` what it is doing besides rendering (a pattern grown), and
// `warning` what the user must hear whatever the verbosity.
class RenderObserver {
  public:
    virtual ~RenderObserver() = default;
    virtual void info(const std::string &) {}
    virtual void note(const std::string &) {}
    virtual void warning(const std::string &) {}
    virtual void frame_written(const FrameReport &) {}
};

// The totals of a run, for --stats-json and the summary line.
struct RenderTotals {
    nlohmann::json frame_stats = nlohmann::json::array();
    RenderStats stats;
    double seconds = 0;  // rendering
    // Loading the scene and building meshes, fur and the BVH; writing the EXRs and
    // previews. With `seconds` they are most of the wall time.
    double setup_seconds = 0, write_seconds = 0, wall_seconds = 0;
    double denoise_seconds = 0;  // film.denoise: the denoiser's share of the wall time
    int rendered = 0, skipped = 0, spp_done = 0;
    int width = 0, height = 0;
    bool animated = false;  // a frame list was given
    std::string first_output, tile;
    // When every frame shares one scene: its triangles and fur.
    bool shared_scene = false;
    size_t triangles = 0;
    bool has_fur = false;
    size_t fur_strands = 0;
    double fur_grow_seconds = 0, fur_embree_seconds = 0;
    // Stopped by the cancel flag: a still keeps what is done (interrupted); a frame of a
    // range is not written (aborted), and --resume redoes it.
    bool interrupted = false, aborted = false;
};

// Runs `job`. Throws pelage::InputError for bad input (before anything is written).
RenderTotals run_render_job(const RenderJob &job, RenderObserver &observer);

// The run's summary as `pelage render --stats-json` writes it: its keys are a contract
// with scripts (docs/guide/scene-format.md).
nlohmann::json render_stats_json(const RenderJob &job, const RenderTotals &totals);

}  // namespace pelage::renderer
