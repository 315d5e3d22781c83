// The explorer's model: one mesh, the preset and seed the page last sent, and a worker
// thread growing them (sim/run/grow_cells.h) — first at a preview scale (fewer, larger
// cells: the same preset with a smaller initial count, so the first pattern shows in a
// fraction of the full run's time), then at full scale, the result `pelage sim` gives for
// the same preset, seed and mesh. While a stage runs, snapshots of its cells become type
// textures (pattern_texture.h) every `snapshot_seconds`; when it ends its statistics are
// measured as `pelage stats --mesh` measures them (pattern/statistics/stats_report.h), on
// a thread of their own so that the next stage or job starts at once. A newer preset
// cancels the run in progress at its next step. A change to nothing but
// the types' look (colours, melanin, names of the whole preset) does not simulate: the
// finished cells are re-labelled with the new preset, which is what growing them again
// would give, since the simulation never reads those keys.
//
// Everything the page shows is in status(), whose `version` grows with every change, so
// a page waits for the next one with a long poll.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "apps/explore/pattern_texture.h"
#include "pattern/mosaic/pattern.h"
#include "sim/crps/surface.h"

namespace pelage::renderer::explore {

struct ExploreOptions {
    std::string mesh;         // a mesh file, FILE#NAME or procedural:...
    std::string preset_dir;   // the shipped presets (scenes/presets)
    std::string work_dir;     // the session's own files (the stages' .cells, the preset)
    int texture_size = 2048;  // doubled, up to max_texture_size, for many triangles
    double snapshot_seconds = 0.25;  // between snapshots of a running stage
    // The preview stage starts from the full count / preview_divisor cells (at least
    // preview_min_cells); none when that is not under half the full count.
    double preview_divisor = 8;
    uint64_t preview_min_cells = 800;
    // The preview grows on a copy of the mesh simplified to its larger cells, kept
    // within this fraction of the bounding-box diagonal of the input.
    double preview_deviation = 0.01;
};

// The largest type texture a page is sent: WebGL implementations take 8192² and more
// (SwiftShader's limit is 8192).
inline constexpr int max_texture_size = 8192;

// The finished full-scale run, for saving and rendering.
struct ExploreResult {
    bool ready = false;
    std::string preset_text;  // the preset as the page sent it (JSON)
    uint64_t seed = 1;
    std::string cells_path;   // in the work folder, labelled with preset_text
    std::string preset_path;  // preset_text, in the work folder
};

class ExploreSession {
  public:
    // Loads the mesh (pelage::InputError when it cannot be read) and starts the worker.
    explicit ExploreSession(ExploreOptions options);
    ~ExploreSession();
    ExploreSession(const ExploreSession &) = delete;
    ExploreSession &operator=(const ExploreSession &) = delete;

    // Checks the preset as the preset parser does (pelage::InputError with its message)
    // and makes it the current one: simulates it (cancelling a run in progress) unless
    // it differs from the last only in its look. Returns the job's number when it
    // simulates, else 0.
    uint64_t submit(const std::string &preset_json, uint64_t seed);

    // The state the page shows, once its version is above `after` or `wait_seconds`
    // have passed.
    nlohmann::json status(uint64_t after, double wait_seconds) const;

    // The input mesh as the page draws it (view_mesh.h), and its version.
    std::vector<uint8_t> mesh_bytes(uint64_t *version) const;
    // The latest type texture (size × size bytes, row y at v = (y + 0.5) / size) and
    // its version.
    std::vector<uint8_t> texture_bytes(uint64_t *version) const;

    ExploreResult result() const;
    // Ends the run in progress at its next step and answers every waiting status() at
    // once (the server is stopping); the session takes no more jobs.
    void shutdown();
    const std::string &mesh() const { return m_options.mesh; }
    const std::string &work_dir() const { return m_options.work_dir; }
    const sim::Surface &input_surface() const { return *m_input; }

  private:
    struct Job {
        uint64_t id = 0;
        std::string preset_text;
        uint64_t seed = 1;
    };
    void work();
    void run_job(const Job &job);
    // The statistics thread: measures the latest finished stage while the worker goes on.
    void measure();
    // A file of job `job` in the work folder. Under m_mutex, prune_files() removes the
    // files of every job but the last two results' (as a result arrives, and after a
    // cancelled job).
    std::string job_file(uint64_t job, const std::string &name) const;
    void prune_files();
    // The preview's surface (a mesh file in the work folder), made on first use; "" when
    // none would help or none keeps to the input.
    std::string preview_surface();
    // Where the layout's samples lie on `surface` (null: it is the input mesh), kept
    // per surface: a preview's surface serves every job.
    const SampleTargets *targets_on(const sim::Surface &surface, const std::string &name);
    // Under m_mutex: records a change for the page.
    void changed();

    ExploreOptions m_options;
    std::unique_ptr<sim::Surface> m_input;  // the mesh as loaded: its area and counts
    uint64_t m_input_hash = 0;
    std::unique_ptr<TypeTextureLayout> m_layout;  // on the input mesh
    bool m_preview_tried = false;                 // the worker's own
    std::string m_preview_mesh;
    std::map<uint64_t, SampleTargets> m_targets;  // the worker's own, by mesh hash

    mutable std::mutex m_mutex;
    mutable std::condition_variable m_changed;
    std::condition_variable m_wake;
    bool m_stop = false;
    Job m_pending;  // the newest job; its id above m_started when not yet begun
    uint64_t m_started = 0;
    uint64_t m_next_id = 0;
    std::string m_sim_key;   // of the newest job: the preset without its look keys
    nlohmann::json m_state;  // what status() reports, less the version
    uint64_t m_version = 1;
    std::vector<uint8_t> m_mesh_bytes, m_texture;
    uint64_t m_mesh_version = 0, m_texture_version = 0;
    ExploreResult m_result;
    std::deque<uint64_t> m_kept;  // the jobs of the last two results: their files stay
    struct Measure {
        uint64_t job = 0;
        std::string stage;
        std::shared_ptr<const pattern::mosaic::MosaicPattern> pattern;
        std::string cells_path;
    };
    Measure m_measure;  // the stage to measure next (pattern null: none)
    std::thread m_worker, m_measurer;
};

// The preset's JSON without the keys the simulation never reads (the types' colours
// and melanins, the preset's name, description, source, notes and published figures):
// two presets with the same key grow the same cells.
std::string simulation_key(const nlohmann::json &preset);

}  // namespace pelage::renderer::explore
