// `pelage sim --mesh FILE --preset NAME|FILE`: grows a Clonal Mosaic on the mesh's CRPS
// and writes the .cells file (sim/mosaic/cm_simulation.h, sim/cells_io/cells_file.h). The
// keys of
// --stats-json are a contract: triangles, area, cells_by_type, spot_fraction,
// divisions, relax_steps, seconds, peak_rss_mb.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "renderer/cli/common.h"
#include "renderer/cli/simulation_surface.h"
#include "renderer/core/progress.h"
#include "sim/cells_io/cells_file.h"
#include "sim/cells_io/pattern_stats.h"
#include "sim/core/input_error.h"
#include "sim/crps/body_length.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/cm_simulation.h"

namespace pelage::renderer::cli {
namespace {

struct SimOptions {
    std::string mesh, preset, output, stats_json, relax;
    std::string surface = "auto";
    uint64_t cells = 0;
    uint64_t seed = 1;
    ThreadOption threads;
};

int run_sim(const SimOptions &o) {
    const auto control = o.threads.apply();
    // --- Inputs first: nothing is written unless every input is good ---
    sim::Preset preset = sim::load_preset(o.preset, data_path("scenes/presets"));
    if (o.relax == "local")
        preset.params.relax = sim::RelaxMode::local;
    else if (o.relax == "global")
        preset.params.relax = sim::RelaxMode::global;

    // --- The simulation surface: the input, or a copy at the cells' scale
    //     (simulation_surface.h) ---
    renderer::SetupPhase::show("pelage sim", renderer::Progress::stderr_is_tty());
    const SimulationSurface chosen(
        [&] {
            const renderer::SetupPhase phase("loading the mesh, building its CRPS");
            return sim::build_surface(o.mesh);
        }(),
        o.mesh, preset, o.cells, o.surface == "auto");
    const sim::Surface &surface = chosen.surface();
    const sim::CellScaleReport &cell_scale = chosen.report();
    const uint64_t initial = chosen.initial_cells();
    if (cell_scale.simplified)
        fmt::print(
            "pelage sim: simulating on {} of the input's {} triangles (edges under "
            "{:.3g} collapsed, surface kept within {:.3g} of the input, final cell "
            "spacing about {:.3g}); the .cells file renders on {} through closest "
            "points, or use --surface input\n",
            cell_scale.output_triangles, cell_scale.input_triangles,
            cell_scale.edge_length, cell_scale.max_deviation, cell_scale.cell_spacing,
            o.mesh);

    sim::CmSimulation simulation(surface.crps, preset.types, preset.params, o.seed);
    {
        // The line names this step; the bar that follows measures the growth alone.
        const renderer::SetupPhase phase("placing and relaxing the initial cells");
        simulation.initialize(initial);
    }
    {
        renderer::Progress progress("pelage sim", 1000,
                                    renderer::Progress::stderr_is_tty());
        uint64_t shown = 0;
        simulation.run([&](double f) {
            const uint64_t now = static_cast<uint64_t>(std::clamp(f, 0.0, 1.0) * 1000);
            if (now > shown) progress.advance(now - shown);
            shown = std::max(shown, now);
        });
        progress.finish();
    }
    const sim::SimStats &st = simulation.stats();
    nlohmann::json params = {
        {"preset", nlohmann::json::parse(preset.json_text)},
        {"mesh", o.mesh},
        {"seed", o.seed},
        {"initial_cells", st.initial_cells},
        {"relax", preset.params.relax == sim::RelaxMode::local ? "local" : "global"},
    };
    nlohmann::json surface_json = {{"input_triangles", cell_scale.input_triangles},
                                   {"triangles", surface.mesh.num_triangles()},
                                   {"simplified", cell_scale.simplified}};
    if (cell_scale.simplified) {
        surface_json["edge_length"] = cell_scale.edge_length;
        surface_json["max_deviation"] = cell_scale.max_deviation;
    }
    params["simulation_surface"] = surface_json;
    const sim::CellsData data =
        sim::make_cells_data(surface.mesh, surface.crps, simulation.types(),
                             simulation.cells(), params.dump(), o.seed);
    if (!o.output.empty()) sim::write_cells_file(o.output, data);

    const sim::PatternStats ps = sim::compute_pattern_stats(data);
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto &[name, n] : ps.cells_by_type) by_type[name] = n;
    const double seconds = st.seconds_total;
    fmt::print("pelage sim: {} on {} ({} triangles, area {:.6g}), seed {}\n", preset.name,
               o.mesh, surface.mesh.num_triangles(), ps.area, o.seed);
    const double body_length = sim::body_axis(surface.crps).length;
    fmt::print("  body length   {:.4g}   initial cell spacing {:.3g} x body length\n",
               body_length,
               std::sqrt(2 * ps.area / (std::sqrt(3.0) * double(st.initial_cells))) /
                   body_length);
    fmt::print("  cells         {} -> {}   {}\n", st.initial_cells, data.num_cells(),
               by_type.dump());
    fmt::print("  spot fraction {:.4f}   spots {}   mean spot area {:.4g}\n",
               ps.spot_fraction, ps.spots, ps.mean_spot_area);
    fmt::print(
        "  divisions     {}   relaxation steps {} (+{} initial, {} mode)   time {:.3g}\n",
        st.divisions, st.relax_steps, st.initial_relax_steps,
        params["relax"].get<std::string>(), st.final_time);
    fmt::print("  seconds       {:.3f}   ({:.3g} cell-steps/s)\n", seconds,
               seconds > 0 ? double(st.cell_steps) / seconds : 0.0);
    if (!o.output.empty()) fmt::print("  wrote         {}\n", o.output);

    if (!o.stats_json.empty()) {
        write_json_file(o.stats_json,
                        {
                            {"preset", preset.name},
                            {"mesh", o.mesh},
                            {"seed", o.seed},
                            {"relax", params["relax"]},
                            {"triangles", surface.mesh.num_triangles()},
                            {"input_triangles", cell_scale.input_triangles},
                            {"simplified", cell_scale.simplified},
                            {"area", ps.area},
                            {"body_length", body_length},
                            {"initial_cells", st.initial_cells},
                            {"final_cells", data.num_cells()},
                            {"cells_by_type", by_type},
                            {"spot_fraction", ps.spot_fraction},
                            {"spots", ps.spots},
                            {"mean_spot_area", ps.mean_spot_area},
                            {"divisions", st.divisions},
                            {"relax_steps", st.relax_steps},
                            {"initial_relax_steps", st.initial_relax_steps},
                            {"end_time", st.final_time},
                            {"final_radius", st.final_radius},
                            {"cell_steps", st.cell_steps},
                            {"seconds", seconds},
                            {"seconds_initial", st.seconds_initial},
                            {"seconds_neighbourhoods", st.seconds_neighbourhoods},
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
    sub->add_option("--cells", o->cells,
                    "Initial cell count (overrides the preset; a preset's target count "
                    "is scaled with it)");
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
    sub->add_option("--stats-json", o->stats_json,
                    "Write the run summary as JSON to this file");
    o->threads.add_to(*sub);
    return [o] { return run_sim(*o); };
}

}  // namespace pelage::renderer::cli
