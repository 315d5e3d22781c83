#include "sim/run/grow_cells.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "sim/cells_io/cells_file.h"
#include "sim/core/content_hash.h"
#include "sim/core/input_error.h"
#include "sim/crps/body_length.h"
#include "sim/crps/surface.h"
#include "sim/growth/growth_shape.h"
#include "sim/mesh/mesh_objects.h"
#include "sim/mosaic/growing_surface.h"
#include "sim/mosaic/preset.h"
#include "sim/run/cells_data.h"
#include "sim/run/setup_step.h"
#include "sim/run/simulation_surface.h"

namespace pelage::sim {
namespace {

// The content of the growth block's mesh keys: a pattern grown through other shapes is
// another pattern.
nlohmann::json growth_mesh_hashes(const sim::Preset &preset) {
    nlohmann::json out = nlohmann::json::array();
    if (preset.growth)
        for (const sim::GrowthKey &k : preset.growth->keys)
            if (k.kind == sim::GrowthKey::Kind::mesh)
                out.push_back(mesh_reference_hash(k.mesh));
    return out;
}

sim::Preset read_preset(const GrowRequest &r) {
    sim::Preset preset =
        sim::load_preset(r.preset, r.preset_dir, r.preset_file, r.preset_field);
    if (r.relax == "local")
        preset.params.relax = sim::RelaxMode::local;
    else if (r.relax == "global")
        preset.params.relax = sim::RelaxMode::global;
    return preset;
}

}  // namespace

GrownCells grow_cells(const GrowRequest &r) {
    GrownCells g;
    g.preset = read_preset(r);
    const SimulationSurface chosen(
        [&] {
            const SetupStep step(r.phase, "loading the mesh, building its CRPS");
            return sim::build_surface(r.mesh);
        }(),
        r.mesh, g.preset, r.initial_cells, r.simplify, r.phase);
    const sim::Surface &surface = chosen.surface();
    g.cell_scale = chosen.report();
    g.triangles = surface.mesh.num_triangles();
    if (g.cell_scale.coarsening && r.note)
        r.note(fmt::format(
            "simulating on {} of the input's {} triangles (edges under {:.3g} collapsed: "
            "its neighbourhoods would unfold about {:.2g} triangles; vertices kept "
            "within "
            "{:.3g} of the input, the input within {:.3g} of the copy, final cell "
            "spacing "
            "about {:.3g}); the .cells file renders on {} through closest points, or use "
            "--surface input",
            g.cell_scale.output_triangles, g.cell_scale.input_triangles,
            g.cell_scale.edge_length, g.cell_scale.neighbourhood_entries,
            g.cell_scale.max_deviation, g.cell_scale.max_input_distance,
            g.cell_scale.cell_spacing, r.mesh));
    else if (g.cell_scale.simplified && r.note)
        r.note(fmt::format(
            "simulating on {} of the input's {} triangles (edges under {:.3g} collapsed, "
            "surface kept within {:.3g} of the input, final cell spacing about {:.3g}); "
            "the .cells file renders on {} through closest points, or use --surface "
            "input",
            g.cell_scale.output_triangles, g.cell_scale.input_triangles,
            g.cell_scale.edge_length, g.cell_scale.max_deviation,
            g.cell_scale.cell_spacing, r.mesh));
    if (g.cell_scale.refine_levels > 0 && r.note)
        r.note(fmt::format(
            "simulating on the input's {} triangles split {} times at their edge "
            "midpoints ({} triangles, the same surface; about {:.0f} cells per input "
            "triangle would make every step meet as many); the .cells file renders on "
            "{} through closest points, or use --surface input",
            g.cell_scale.input_triangles, g.cell_scale.refine_levels,
            g.cell_scale.output_triangles, g.cell_scale.input_cells_per_triangle,
            r.mesh));

    // A growing run (the preset's "growth") simulates on the surface's shape at each
    // age and writes the cells on the rest shape, where they keep their barycentric
    // points (sim/mosaic/growing_surface.h).
    std::unique_ptr<sim::GrowingSurface> growing;
    if (g.preset.growth) {
        const SetupStep step(r.phase, "resolving the growth keys on the surface");
        const bool reload = g.cell_scale.remeshed() && g.preset.growth->has_mesh_keys();
        const sim::TriangleMesh rest =
            reload ? sim::load_mesh(r.mesh) : sim::TriangleMesh();
        const sim::GrowthSpec &spec = *g.preset.growth;
        if (const size_t out =
                sim::vertices_outside_cylinders(spec.cylinders, surface.mesh);
            !spec.cylinders.empty() && out > 0 && r.note)
            r.note(
                fmt::format("{} of the surface's {} vertices lie in no growth cylinder "
                            "and keep their rest position at every age (the cylinders "
                            "of {} should enclose the body)",
                            out, surface.mesh.num_vertices(), r.preset));
        growing = std::make_unique<sim::GrowingSurface>(
            surface.mesh, surface.crps,
            sim::resolve_growth(*g.preset.growth, reload ? rest : surface.mesh,
                                surface.mesh));
    }
    sim::CmSimulation simulation(growing ? growing->crps() : surface.crps, g.preset.types,
                                 g.preset.params, r.seed);
    if (growing && g.preset.growth->during) simulation.set_growth(growing.get());
    if (!g.preset.control.empty()) {
        // Resolved on the rest shape, where the preset's box-space points and heights
        // are meant; the values ride on the skin as it grows.
        const SetupStep step(r.phase, "resolving regions on the surface");
        simulation.set_control(sim::SurfaceControl(
            g.preset.control, surface.mesh, surface.crps, r.preset, &chosen.data_mesh()));
    }
    {
        // The line names this step; the bar that follows measures the growth alone.
        const SetupStep step(r.phase, "placing and relaxing the initial cells");
        // On a growing surface the preset's count or density applies to the first
        // age's shape.
        simulation.initialize(growing ? r.initial_cells : chosen.initial_cells());
        if (growing && !g.preset.growth->during)
            g.stats.growth.push_back(
                {growing->age(), simulation.area(), simulation.cells().size()});
    }
    // The live view's snapshot: on a growing surface the cells are carried to the rest
    // shape, as the file keeps them.
    auto look = [&] {
        if (r.cancelled && r.cancelled()) throw GrowCancelled{};
        if (!r.snapshot || !r.snapshot_due || !r.snapshot_due()) return;
        sim::Cells cells = simulation.cells();
        if (growing) sim::carry_cells(growing->crps(), surface.crps, cells);
        r.snapshot(surface, sim::make_cells_data(surface.mesh, surface.crps,
                                                 simulation.types(), cells, "", r.seed));
    };
    look();
    if (r.progress) r.progress(0);
    simulation.run([&](double f) {
        if (r.progress) r.progress(f);
        look();
    });
    {
        // Pattern before growth: the one sample is the start.
        std::vector<sim::GrowthSample> before = std::move(g.stats.growth);
        g.stats = simulation.stats();
        if (!before.empty()) g.stats.growth = before;
    }
    g.params = {
        {"preset", nlohmann::json::parse(g.preset.json_text)},
        {"mesh", r.mesh},
        {"mesh_xxh3", mesh_reference_hash(r.mesh)},
        {"seed", r.seed},
        {"initial_cells", g.stats.initial_cells},
        {"relax", g.preset.params.relax == sim::RelaxMode::local ? "local" : "global"},
    };
    // What the fur's `"comb": "field"` needs of the pattern travels in the file.
    g.params["anisotropy_field"] = recorded_anisotropy_field(g.params["preset"]);
    if (const nlohmann::json h = growth_mesh_hashes(g.preset); !h.empty())
        g.params["growth_meshes_xxh3"] = h;  // absent without mesh keys: files unchanged
    nlohmann::json surface_json = {{"input_triangles", g.cell_scale.input_triangles},
                                   {"triangles", g.triangles},
                                   {"simplified", g.cell_scale.simplified}};
    if (g.cell_scale.refine_levels > 0)
        surface_json["refine_levels"] = g.cell_scale.refine_levels;
    if (g.cell_scale.simplified) {
        surface_json["edge_length"] = g.cell_scale.edge_length;
        surface_json["max_deviation"] = g.cell_scale.max_deviation;
        if (g.cell_scale.coarsening)
            surface_json["max_input_distance"] = g.cell_scale.max_input_distance;
    }
    g.params["simulation_surface"] = surface_json;
    sim::Cells on_rest;
    if (growing) {
        on_rest = simulation.cells();
        sim::carry_cells(growing->crps(), surface.crps, on_rest);
    }
    g.data = sim::make_cells_data(surface.mesh, surface.crps, simulation.types(),
                                  growing ? on_rest : simulation.cells(), g.params.dump(),
                                  r.seed);
    g.body_length = sim::body_axis(surface.crps).length;
    return g;
}

bool cells_match(const std::string &path, const GrowRequest &r, std::string *why) {
    auto differs = [&](const std::string &what) {
        if (why) *why = what;
        return false;
    };
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return differs("no file");
    nlohmann::json params;
    try {
        params = nlohmann::json::parse(sim::read_cells_params(path));
    } catch (const std::exception &) {
        return differs("unreadable");
    }
    const sim::Preset preset = read_preset(r);
    if (!params.contains("preset") ||
        params["preset"] != nlohmann::json::parse(preset.json_text))
        return differs("grown from another preset");
    if (params.value("seed", uint64_t(0)) != r.seed)
        return differs("grown with another seed");
    if (params.value("mesh_xxh3", std::string()) != mesh_reference_hash(r.mesh))
        return differs("grown on another mesh");
    if (params.value("growth_meshes_xxh3", nlohmann::json::array()) !=
        growth_mesh_hashes(preset))
        return differs("grown through other growth meshes");
    const std::string relax =
        preset.params.relax == sim::RelaxMode::local ? "local" : "global";
    if (params.value("relax", std::string()) != relax)
        return differs("grown with another relaxation");
    if (r.initial_cells > 0 &&
        params.value("initial_cells", uint64_t(0)) != r.initial_cells)
        return differs("grown from another cell count");
    // The same cells, but the fur's "comb": "field" reads the field the file records.
    if (!params.contains("anisotropy_field"))
        return differs("written by an older pelage (no anisotropy field recorded)");
    return true;
}

}  // namespace pelage::sim
