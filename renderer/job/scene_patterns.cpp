#include "renderer/job/scene_patterns.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "renderer/core/install_layout.h"
#include "renderer/core/progress.h"
#include "renderer/core/setup_phase.h"
#include "sim/cells_io/cells_file.h"

namespace pelage::renderer {

sim::GrownCells grow_cells_shown(sim::GrowRequest r, const std::string &label,
                                 bool show) {
    r.preset_dir = find_data("scenes/presets");
    const bool tty = show && Progress::stderr_is_tty();
    SetupPhase::show(label, tty);
    std::optional<SetupPhase> phase;
    r.phase = [&](const std::string &name) {
        phase.reset();
        if (!name.empty()) phase.emplace(name);
    };
    // The bar measures the growth alone: it starts when the run reports 0.
    std::optional<Progress> bar;
    uint64_t shown = 0;
    r.progress = [&](double f) {
        if (!bar) bar.emplace(label, 1000, tty);
        const uint64_t now = static_cast<uint64_t>(std::clamp(f, 0.0, 1.0) * 1000);
        if (now > shown) bar->advance(now - shown);
        shown = std::max(shown, now);
    };
    sim::GrownCells grown = sim::grow_cells(r);
    if (bar) bar->finish();
    return grown;
}

void grow_scene_patterns(const SceneDesc &scene,
                         const std::function<void(const std::string &)> &note,
                         bool show) {
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const ObjectDesc &o = scene.objects[i];
        if (!o.pattern) continue;
        sim::GrowRequest request;
        request.mesh = o.mesh;
        request.preset = o.pattern->preset;
        request.preset_dir = find_data("scenes/presets");
        request.preset_file = scene.path;
        request.preset_field = "objects[" + std::to_string(i) + "].pattern.preset";
        request.seed = o.pattern->seed;
        std::string why;
        if (sim::cells_match(o.cells, request, &why)) {
            // Said, so that a user who expects a new coat knows why none was grown.
            if (note)
                note(
                    fmt::format("{}: grown from the same mesh, preset and seed; reused "
                                "(delete it to grow the pattern again)",
                                o.cells));
            continue;
        }
        if (note)
            note(fmt::format("{}: {}, growing {} (seed {}) on {}", o.cells, why,
                             o.pattern->preset, o.pattern->seed, o.mesh));
        const auto start = std::chrono::steady_clock::now();
        const sim::GrownCells grown =
            grow_cells_shown(request, "pattern of " + o.name, show);
        sim::write_cells_file(o.cells, grown.data);
        if (note)
            note(fmt::format(
                "{}: {} cells, {:.1f} s", o.cells, grown.data.num_cells(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                    .count()));
    }
}

void grow_scene_patterns(const SceneDesc &scene, bool quiet) {
    std::function<void(const std::string &)> note;
    if (!quiet)
        note = [](const std::string &line) {
            std::fprintf(stderr, "%s\n", line.c_str());
        };
    grow_scene_patterns(scene, note, !quiet);
}

}  // namespace pelage::renderer
