#include "renderer/cli/grow_shown.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "renderer/cli/common.h"
#include "renderer/core/progress.h"
#include "renderer/core/setup_phase.h"
#include "sim/cells_io/cells_file.h"

namespace pelage::renderer::cli {

sim::GrownCells grow_cells_shown(sim::GrowRequest r, const std::string &label,
                                 bool show) {
    r.preset_dir = data_path("scenes/presets");
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

void grow_scene_patterns(const SceneDesc &scene, bool quiet) {
    for (const ObjectDesc &o : scene.objects) {
        if (!o.pattern) continue;
        sim::GrowRequest request;
        request.mesh = o.mesh;
        request.preset = o.pattern->preset;
        request.preset_dir = data_path("scenes/presets");
        request.seed = o.pattern->seed;
        std::string why;
        if (sim::cells_match(o.cells, request, &why)) continue;
        if (!quiet)
            std::fprintf(stderr, "%s: %s, growing %s (seed %llu) on %s\n",
                         o.cells.c_str(), why.c_str(), o.pattern->preset.c_str(),
                         static_cast<unsigned long long>(o.pattern->seed),
                         o.mesh.c_str());
        const Timer timer;
        const sim::GrownCells grown =
            grow_cells_shown(request, "pattern of " + o.name, !quiet);
        sim::write_cells_file(o.cells, grown.data);
        if (!quiet)
            std::fprintf(stderr, "%s: %zu cells, %.1f s\n", o.cells.c_str(),
                         grown.data.num_cells(), timer.seconds());
    }
}

}  // namespace pelage::renderer::cli
