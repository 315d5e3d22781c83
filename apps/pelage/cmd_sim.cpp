// `pelage sim --mesh FILE --preset NAME|FILE`: grows a Clonal Mosaic on the mesh's CRPS
// and writes the .cells file (sim/mosaic/cm_simulation.h, sim/cells_io/cells_file.h). The
// keys of --stats-json are a contract: triangles, area, cells_by_type, spot_fraction (by
// count), divisions, relax_steps, seconds, peak_rss_mb; growth (a growing run: time,
// area, cells, density at each reshape and at the end; empty otherwise) and
// growth_lost_cells. The spots are measured by `pelage stats` on the file written.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/common/common.h"
#include "renderer/job/scene_patterns.h"
#include "sim/cells_io/cells_file.h"
#include "sim/cells_report/pattern_stats.h"
#include "sim/core/input_error.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

struct SimOptions {
    std::string mesh, preset, output, relax;
    std::string surface = "auto";
    uint64_t cells = 0;
    uint64_t seed = 1;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

int run_sim(const SimOptions &o) {
    const auto control = o.threads.apply();
    if (o.output.empty())
        std::fprintf(stderr,
                     "pelage sim: warning: no -o given, the cells will not be saved "
                     "(only the summary%s is written)\n",
                     o.stats_json.wanted() ? " and --stats-json" : "");
    sim::GrowRequest request;
    request.mesh = o.mesh;
    request.preset = o.preset;
    request.seed = o.seed;
    request.initial_cells = o.cells;
    request.relax = o.relax;
    request.simplify = o.surface == "auto";
    if (!o.quiet)
        request.note = [](const std::string &text) {
            fmt::print("pelage sim: {}\n", text);
        };
    // Inputs first: grow_cells() reads and checks them all before simulating, and
    // nothing is written unless the run succeeds.
    const sim::GrownCells grown = grow_cells_shown(request, "pelage sim", !o.quiet);
    const sim::Preset &preset = grown.preset;
    const sim::SimStats &st = grown.stats;
    const sim::CellScaleReport &cell_scale = grown.cell_scale;
    const nlohmann::json &params = grown.params;
    const sim::CellsData &data = grown.data;
    if (!o.output.empty()) sim::write_cells_file(o.output, data);

    const sim::PatternStats ps = sim::compute_pattern_stats(data);
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto &[name, n] : ps.cells_by_type) by_type[name] = n;
    const double seconds = st.seconds_total;
    const double body_length = grown.body_length;
    if (!o.quiet) {
        fmt::print("pelage sim: {} on {} ({} triangles, area {:.6g}), seed {}\n",
                   preset.name, o.mesh, grown.triangles, ps.area, o.seed);
        fmt::print("  body length   {:.4g}   initial cell spacing {:.3g} x body length\n",
                   body_length,
                   std::sqrt(2 * ps.area / (std::sqrt(3.0) * double(st.initial_cells))) /
                       body_length);
        fmt::print("  cells         {} -> {}   {}\n", st.initial_cells, data.num_cells(),
                   by_type.dump());
        fmt::print("  spot fraction {:.4f} by count (spots: pelage stats FILE.cells)\n",
                   ps.spot_fraction);
        fmt::print(
            "  divisions     {}   relaxation steps {} (+{} initial, {} mode)   time "
            "{:.3g}\n",
            st.divisions, st.relax_steps, st.initial_relax_steps,
            params["relax"].get<std::string>(), st.final_time);
        fmt::print("  seconds       {:.3f}   ({:.3g} cell-steps/s)\n", seconds,
                   seconds > 0 ? double(st.cell_steps) / seconds : 0.0);
        if (!o.output.empty()) fmt::print("  wrote         {}\n", o.output);
    }

    // A growing run: cells per unit area at every reshape (Walter thesis §6.2 keeps it
    // constant).
    nlohmann::json growth = nlohmann::json::array();
    for (const sim::GrowthSample &g : st.growth)
        growth.push_back({{"time", g.time},
                          {"area", g.area},
                          {"cells", g.cells},
                          {"density", double(g.cells) / g.area}});
    if (!o.quiet && st.growth.size() > 1) {
        const sim::GrowthSample &a = st.growth.front(), &b = st.growth.back();
        fmt::print(
            "  growth        area {:.4g} -> {:.4g}   cells per unit area {:.4g} -> "
            "{:.4g} ({} reshapes)\n",
            a.area, b.area, double(a.cells) / a.area, double(b.cells) / b.area,
            st.growth.size() - 1);
    }

    if (o.stats_json.wanted()) {
        o.stats_json.write({
            {"growth", growth},
            {"growth_lost_cells", st.growth_lost_cells},
            {"preset", preset.name},
            {"mesh", o.mesh},
            {"seed", o.seed},
            {"relax", params["relax"]},
            {"triangles", grown.triangles},
            {"input_triangles", cell_scale.input_triangles},
            {"simplified", cell_scale.simplified},
            {"refine_levels", cell_scale.refine_levels},
            {"coarsened", cell_scale.coarsening},
            {"pre_collapsed_triangles", cell_scale.pre_collapsed_triangles},
            {"neighbourhood_entries_estimate", cell_scale.neighbourhood_entries},
            {"area", ps.area},
            {"body_length", body_length},
            {"initial_cells", st.initial_cells},
            {"final_cells", data.num_cells()},
            {"cells_by_type", by_type},
            {"spot_fraction", ps.spot_fraction},
            {"divisions", st.divisions},
            {"relax_steps", st.relax_steps},
            {"initial_relax_steps", st.initial_relax_steps},
            {"end_time", st.final_time},
            {"final_radius", st.final_radius},
            {"cell_steps", st.cell_steps},
            {"seconds", seconds},
            {"seconds_initial", st.seconds_initial},
            {"seconds_neighbourhoods", st.seconds_neighbourhoods},
            {"seconds_force_sum", st.seconds_force_sum},
            {"interacting_pairs", st.interacting_pairs},
            {"peak_rss_mb", peak_rss_mb()},
            {"cells_steps_per_second",
             seconds > 0 ? double(st.cell_steps) / seconds : 0.0},
        });
    }
    return 0;
}

}  // namespace

Runner add_sim_command(CLI::App &app) {
    auto o = std::make_shared<SimOptions>();
    CLI::App *sub = app.add_subcommand(
        "sim", "Grow a Clonal Mosaic on a mesh and write a .cells file");
    sub->add_option(
           "--mesh", o->mesh,
           "Mesh file (.off, .obj, .gltf, .glb, .fbx, .ply, .dae, ...), FILE#NAME for "
           "one named object of it, or procedural:sphere:20x20 ...")
        ->required();
    sub->add_option("--preset", o->preset,
                    "Preset name (scenes/presets/NAME.json) or a preset file")
        ->required();
    sub->add_option("--initial-cells", o->cells,
                    "Initial cell count (overrides the preset; a preset's target count "
                    "is scaled with it)")
        ->default_str("");
    sub->add_option("--seed", o->seed,
                    "Seed: same mesh, preset and seed give identical .cells");
    sub->add_option("--relax", o->relax, "Relaxation mode (overrides the preset)")
        ->check(CLI::IsMember({"local", "global"}));
    sub->add_option("--surface", o->surface,
                    "auto: simulate on a copy of the mesh simplified to the cells' scale "
                    "when its triangles are smaller than the cells; input: on the mesh "
                    "as it is")
        ->check(CLI::IsMember({"auto", "input"}))
        ->capture_default_str();
    sub->add_option("-o,--output", o->output, "Write the cells to this .cells file");
    o->stats_json.add_to(*sub, "the run summary");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run_sim(*o); };
}

}  // namespace pelage::renderer::cli
