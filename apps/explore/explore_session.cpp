#include "apps/explore/explore_session.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "apps/explore/pattern_texture.h"
#include "apps/explore/preview_surface.h"
#include "apps/explore/view_mesh.h"
#include "pattern/mosaic/pattern.h"
#include "pattern/statistics/stats_report.h"
#include "pattern/transfer/surface_transfer.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_write_obj.h"
#include "sim/mosaic/cm_simulation.h"
#include "sim/mosaic/preset.h"
#include "sim/run/cells_data.h"
#include "sim/run/grow_cells.h"

namespace pelage::renderer::explore {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

std::string simulation_key(const nlohmann::json &preset) {
    nlohmann::json j = preset;
    for (const char *k : {"name", "description", "source", "notes", "published"})
        j.erase(k);
    if (j.contains("types") && j["types"].is_array())
        for (nlohmann::json &t : j["types"])
            if (t.is_object())
                for (const char *k :
                     {"colour", "color", "eumelanin", "pheomelanin", "notes"})
                    t.erase(k);
    return j.dump();
}

ExploreSession::ExploreSession(ExploreOptions options) : m_options(std::move(options)) {
    m_input = std::make_unique<sim::Surface>(sim::build_surface(m_options.mesh));
    m_input_hash = sim::mesh_hash(m_input->mesh);
    std::filesystem::create_directories(m_options.work_dir);
    // The page draws the input mesh whatever surface a stage simulates on.
    // A mesh of many small triangles needs a larger texture for its tiles of at least
    // 2 × 2 texels (the cow split four times, 1.5 M triangles: 4096²).
    const double n = double(m_input->mesh.num_triangles());
    int size = m_options.texture_size;
    while (size < max_texture_size && double(size) * size < 6 * n) size *= 2;
    if (double(size) * size < 6 * n)
        throw InputError(m_options.mesh, 0, "",
                         std::to_string(m_input->mesh.num_triangles()) +
                             " triangles: the explorer draws at most " +
                             std::to_string(max_texture_size * max_texture_size / 6) +
                             " (simplify the mesh for exploring; `pelage sim` and "
                             "`pelage look` take it as it is)");
    m_layout =
        std::make_unique<TypeTextureLayout>(layout_type_texture(m_input->mesh, size));
    m_mesh_bytes = view_mesh_bytes(m_input->mesh, *m_layout);
    m_mesh_version = 1;
    m_state = {{"stage", ""},           {"phase", ""},       {"progress", 0.0},
               {"running", false},      {"error", ""},       {"job", 0},
               {"stats", nullptr},      {"stats_stage", ""}, {"timing", {}},
               {"mesh", m_options.mesh}};
    m_worker = std::thread([this] { work(); });
    m_measurer = std::thread([this] { measure(); });
}

void ExploreSession::shutdown() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
    }
    m_wake.notify_all();
    m_changed.notify_all();
}

ExploreSession::~ExploreSession() {
    shutdown();
    m_worker.join();
    m_measurer.join();
}

void ExploreSession::changed() {
    ++m_version;
    m_changed.notify_all();
}

uint64_t ExploreSession::submit(const std::string &preset_json, uint64_t seed) {
    // The parser's own checks and messages; the file name is the page's field.
    const sim::Preset preset = sim::parse_preset(preset_json, "preset");
    if (preset.growth && preset.growth->has_mesh_keys())
        throw InputError("preset", 0, "growth",
                         "growth keys that name mesh files are not explored (grow it "
                         "with `pelage sim`)");
    const nlohmann::json parsed = nlohmann::json::parse(preset_json);
    const std::string key = simulation_key(parsed) + "#" + std::to_string(seed);
    std::lock_guard lock(m_mutex);
    m_state["preset"] = parsed;
    m_state["seed"] = seed;
    nlohmann::json types = nlohmann::json::array();
    for (const sim::CellType &t : preset.types.types())
        types.push_back({{"name", t.name}, {"colour", t.colour}});
    m_state["types"] = types;
    if (key == m_sim_key) {
        // The same cells: the finished ones are labelled with the new preset when the
        // worker is idle, else the running job takes the new text at its end.
        m_pending.preset_text = preset_json;
        if (m_result.ready) {
            sim::CellsData data = sim::read_cells_file(m_result.cells_path);
            nlohmann::json params = nlohmann::json::parse(data.params_json);
            params["preset"] = nlohmann::json::parse(preset.json_text);
            data.params_json = params.dump();
            data.types = sim::cells_file_types(preset.types);
            sim::write_cells_file(m_result.cells_path, data);
            write_file_atomically(m_result.preset_path,
                                  [&](std::ostream &out) { out << preset_json; });
            m_result.preset_text = preset_json;
        }
        changed();
        return 0;
    }
    m_sim_key = key;
    m_pending = {++m_next_id, preset_json, seed};
    m_result.ready = false;
    m_state["job"] = m_pending.id;
    m_state["running"] = true;
    m_state["error"] = "";
    m_state["stage"] = "";
    m_state["progress"] = 0.0;
    m_state["stats"] = nullptr;
    m_state["stats_stage"] = "";
    m_state["timing"] = nlohmann::json::object();
    changed();
    m_wake.notify_all();
    return m_pending.id;
}

nlohmann::json ExploreSession::status(uint64_t after, double wait_seconds) const {
    std::unique_lock lock(m_mutex);
    m_changed.wait_for(lock, std::chrono::duration<double>(wait_seconds),
                       [&] { return m_version > after || m_stop; });
    nlohmann::json j = m_state;
    j["version"] = m_version;
    j["mesh_version"] = m_mesh_version;
    j["texture_version"] = m_texture_version;
    j["texture_size"] = m_layout->size;
    j["result_ready"] = m_result.ready;
    return j;
}

std::vector<uint8_t> ExploreSession::mesh_bytes(uint64_t *version) const {
    std::lock_guard lock(m_mutex);
    *version = m_mesh_version;
    return m_mesh_bytes;
}

std::vector<uint8_t> ExploreSession::texture_bytes(uint64_t *version) const {
    std::lock_guard lock(m_mutex);
    *version = m_texture_version;
    return m_texture;
}

ExploreResult ExploreSession::result() const {
    std::lock_guard lock(m_mutex);
    return m_result;
}

void ExploreSession::work() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stop || m_pending.id > m_started; });
            if (m_stop) return;
            job = m_pending;
            m_started = job.id;
        }
        try {
            run_job(job);
        } catch (const sim::GrowCancelled &) {
            std::lock_guard lock(m_mutex);
            prune_files();
            // A newer job is pending: the loop takes it.
        } catch (const std::exception &e) {
            std::lock_guard lock(m_mutex);
            prune_files();
            if (m_pending.id == job.id) {
                m_state["error"] = e.what();
                m_state["running"] = false;
                changed();
            }
        }
    }
}

std::string ExploreSession::preview_surface() {
    if (m_preview_tried) return m_preview_mesh;
    m_preview_tried = true;
    const std::optional<sim::TriangleMesh> coarse = simplify_for_preview(
        m_input->mesh, m_options.preview_divisor, m_options.preview_deviation);
    if (!coarse) return "";
    m_preview_mesh = m_options.work_dir + "/preview_surface.obj";
    sim::write_obj(m_preview_mesh, *coarse, {});
    return m_preview_mesh;
}

const SampleTargets *ExploreSession::targets_on(const sim::Surface &surface,
                                                const std::string &name) {
    const uint64_t h = sim::mesh_hash(surface.mesh);
    if (h == m_input_hash) return nullptr;
    auto it = m_targets.find(h);
    if (it == m_targets.end()) {
        if (m_targets.size() >= 4) m_targets.clear();
        const pattern::transfer::SurfaceTransfer transfer(surface, m_input->mesh, name,
                                                          m_options.mesh);
        it = m_targets.emplace(h, map_samples(*m_layout, transfer)).first;
    }
    return &it->second;
}

void ExploreSession::run_job(const Job &job) {
    const Clock::time_point t0 = Clock::now();
    const std::string preset_path = job_file(job.id, "preset.json");
    write_file_atomically(preset_path,
                          [&](std::ostream &out) { out << job.preset_text; });
    const sim::Preset preset = sim::parse_preset(job.preset_text, preset_path);
    const uint64_t full = sim::initial_cell_count(preset.params, m_input->crps);
    const uint64_t preview = std::max<uint64_t>(
        m_options.preview_min_cells,
        uint64_t(std::llround(double(full) / m_options.preview_divisor)));
    struct Stage {
        const char *name;
        uint64_t cells;    // 0: the preset's own count
        std::string mesh;  // the surface it grows on
        bool simplify;     // to the cells' scale, as `pelage sim` does
    };
    std::vector<Stage> stages;
    if (2 * preview < full)
        if (const std::string coarse = preview_surface(); !coarse.empty())
            stages.push_back({"preview", preview, coarse, false});
    stages.push_back({"full", 0, m_options.mesh, true});

    auto stale = [&] {
        std::lock_guard lock(m_mutex);
        return m_stop || m_pending.id != job.id;
    };
    double texture_seconds = 0;  // what the last snapshot's texture took
    auto show = [&](const sim::Crps &crps, const sim::CellsData &cells,
                    const SampleTargets *targets, const char *stage) {
        const Clock::time_point start = Clock::now();
        std::vector<uint8_t> texture = type_texture(*m_layout, crps, cells, targets);
        texture_seconds = since(start);
        std::lock_guard lock(m_mutex);
        if (m_pending.id != job.id) return;
        m_texture = std::move(texture);
        ++m_texture_version;
        m_state["texture_stage"] = stage;
        m_state["texture_job"] = job.id;
        m_state["texture_seconds"] = texture_seconds;
        m_state["texture_cells"] = cells.num_cells();
        if (!m_state["timing"].contains("first_pattern_seconds"))
            m_state["timing"]["first_pattern_seconds"] = since(t0);
        changed();
    };

    for (const Stage &stage : stages) {
        {
            std::lock_guard lock(m_mutex);
            m_state["stage"] = stage.name;
            m_state["progress"] = 0.0;
            changed();
        }
        Clock::time_point last_snapshot = Clock::now() - std::chrono::hours(1);
        Clock::time_point last_progress = last_snapshot;
        sim::GrowRequest r;
        r.mesh = stage.mesh;
        r.simplify = stage.simplify;
        r.preset = preset_path;
        r.preset_dir = m_options.preset_dir;
        r.seed = job.seed;
        r.initial_cells = stage.cells;
        r.phase = [&](const std::string &phase) {
            std::lock_guard lock(m_mutex);
            m_state["phase"] = phase;
            changed();
        };
        r.progress = [&](double f) {
            if (since(last_progress) < 0.1 && f < 1) return;
            last_progress = Clock::now();
            std::lock_guard lock(m_mutex);
            m_state["progress"] = f;
            changed();
        };
        r.cancelled = stale;
        // Snapshots take at most a quarter of the time: the texture of 100 000 cells
        // takes longer than the interval.
        r.snapshot_due = [&] {
            return since(last_snapshot) >=
                   std::max(m_options.snapshot_seconds, 3 * texture_seconds);
        };
        r.snapshot = [&](const sim::Surface &surface, sim::CellsData &&cells) {
            show(surface.crps, cells, targets_on(surface, stage.mesh), stage.name);
            last_snapshot = Clock::now();
        };
        const sim::GrownCells grown = sim::grow_cells(r);
        const std::string cells_path =
            job_file(job.id, std::string(stage.name) + ".cells");
        sim::write_cells_file(cells_path, grown.data);
        // The finished cells as the renderer finds them: on the input mesh, through the
        // same pattern class (and its surface transfer) `pelage stats --mesh` uses.
        auto pattern = std::make_shared<const pattern::mosaic::MosaicPattern>(
            cells_path, m_options.mesh);
        show(pattern->surface().crps, pattern->data(),
             targets_on(pattern->surface(), stage.mesh), stage.name);
        {
            std::lock_guard lock(m_mutex);
            if (m_pending.id != job.id) throw sim::GrowCancelled{};
            m_state["timing"][std::string(stage.name) + "_seconds"] = since(t0);
            if (std::string(stage.name) == "full") {
                m_state["running"] = false;
                m_state["progress"] = 1.0;
                // A look-only change that arrived while this ran is the job's text now.
                const std::string text = m_pending.preset_text;
                if (text != job.preset_text) {
                    sim::CellsData data = grown.data;
                    const sim::Preset now = sim::parse_preset(text, "preset");
                    nlohmann::json params = nlohmann::json::parse(data.params_json);
                    params["preset"] = nlohmann::json::parse(now.json_text);
                    data.params_json = params.dump();
                    data.types = sim::cells_file_types(now.types);
                    sim::write_cells_file(cells_path, data);
                }
                write_file_atomically(preset_path,
                                      [&](std::ostream &out) { out << text; });
                m_result = {true, text, job.seed, cells_path, preset_path};
                m_kept.push_back(job.id);
                if (m_kept.size() > 2) m_kept.pop_front();
                prune_files();
            }
            // Measured beside the next stage or job: a change made as a run ends starts
            // at once.
            m_measure = {job.id, stage.name, pattern, cells_path};
            changed();
        }
        m_wake.notify_all();
    }
}

void ExploreSession::measure() {
    for (;;) {
        Measure m;
        {
            std::unique_lock lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stop || m_measure.pattern; });
            if (m_stop) return;
            m = std::move(m_measure);
            m_measure = {};
        }
        const nlohmann::json stats =
            pattern::statistics::stats_report(*m.pattern, m.cells_path, {});
        std::lock_guard lock(m_mutex);
        if (m_pending.id != m.job) continue;
        m_state["stats"] = stats;
        m_state["stats_stage"] = m.stage;
        changed();
    }
}

std::string ExploreSession::job_file(uint64_t job, const std::string &name) const {
    return m_options.work_dir + "/job" + std::to_string(job) + "_" + name;
}

void ExploreSession::prune_files() {
    const std::vector<uint64_t> kept(m_kept.begin(), m_kept.end());
    std::error_code ec;
    for (const auto &e : std::filesystem::directory_iterator(m_options.work_dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("job", 0) != 0) continue;
        const uint64_t id = std::strtoull(name.c_str() + 3, nullptr, 10);
        if (std::find(kept.begin(), kept.end(), id) == kept.end())
            std::filesystem::remove(e.path(), ec);
    }
}

}  // namespace pelage::renderer::explore
