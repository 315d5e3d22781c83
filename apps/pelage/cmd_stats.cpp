// `pelage stats FILE.cells [--mesh MESH] [--json]`: pattern statistics of a .cells file.
// JSON keys are a contract. Counts (sim/cells_report/pattern_stats.h): cells_by_type,
// spot_fraction. The look as the renderer shows it, measured through the closest-cell
// search on the surface the cells were grown on (the one the file carries, or --mesh):
// the area each type covers (pattern/statistics/area_fractions.h): area_fraction_by_type,
// spot_fraction_by_area, area_samples; the spots (pattern/statistics/spot_statistics.h,
// pelage's one definition of a spot): spot_count, spot_area_mean, spot_area_sd,
// spot_area_share_mean, spot_area_quantiles, largest_spot_cells, spot_neighbours_mean,
// spot_circularity_mean, spot_complexity, background_components,
// background_largest_share, background_near_spot, grid_resolution; for cells grown with
// anisotropy, how their F/B boundaries follow its field
// (sim/cells_report/stripe_alignment.h): stripe_alignment_median, stripe_alignment_q1,
// stripe_alignment_q3 (degrees), stripe_alignment_samples, stripe_coherence_median; and,
// with --mesh when the preset has neural-crest masks, mask_adherence
// (pattern/statistics/mask_adherence.h).
#include <fmt/core.h>

#include <cstdio>
#include <iostream>

#include "apps/common/common.h"
#include "pattern/statistics/mask_adherence.h"
#include "pattern/statistics/stats_report.h"
#include "sim/cells_io/cells_file.h"
#include "sim/cells_report/pattern_stats.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

struct StatsOptions {
    std::string file, mesh, preset;
    bool json = false;
    size_t area_samples = 200000;
    double grid_resolution = 6;
    uint64_t seed = 1;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

// The mask adherence keys, one object per mask.
nlohmann::json to_json(const std::vector<pattern::statistics::MaskAdherence> &a) {
    nlohmann::json j = nlohmann::json::array();
    for (const pattern::statistics::MaskAdherence &m : a)
        j.push_back({{"type", m.type},
                     {m.only_in ? "only_in" : "not_in", m.region},
                     {"otherwise", m.otherwise},
                     {"masked_out_share", m.masked_out_share},
                     {"masked_out_samples", m.masked_out_samples},
                     {"violation", m.violation}});
    return j;
}

// The pattern on --mesh when given (its shape is checked), else on the file's own
// surface.
pattern::mosaic::MosaicPattern load_pattern(const StatsOptions &o) {
    if (o.mesh.empty()) return pattern::mosaic::MosaicPattern(o.file);
    return pattern::mosaic::MosaicPattern(o.file, o.mesh);
}

// Adds mask_adherence when the preset (given, else the file's) has neural-crest masks;
// the masks' attributes and UVs come from the mesh file.
void add_mask_adherence(const StatsOptions &o,
                        const pattern::mosaic::MosaicPattern &pattern,
                        nlohmann::json *j) {
    // The preset given, else the one the file was grown from.
    std::string preset_file = o.preset;
    const sim::Preset preset = [&] {
        if (!o.preset.empty())
            return sim::load_preset(o.preset, data_path("scenes/presets"));
        preset_file = o.file;
        const auto params =
            nlohmann::json::parse(pattern.data().params_json, nullptr, false);
        if (params.is_discarded() || !params.contains("preset")) return sim::Preset{};
        return sim::parse_preset(params["preset"].dump(), o.file);
    }();
    if (!preset.control.masks.empty())
        (*j)["mask_adherence"] = to_json(pattern::statistics::measure_mask_adherence(
            pattern, o.mesh, preset, preset_file, o.area_samples, o.seed));
}

int run_stats(const StatsOptions &o) {
    const pattern::mosaic::MosaicPattern pattern = load_pattern(o);
    const sim::CellsData &data = pattern.data();
    const sim::PatternStats s = sim::compute_pattern_stats(data);
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto &[name, n] : s.cells_by_type) by_type[name] = n;
    std::string warning;
    nlohmann::json j = pattern::statistics::stats_report(
        pattern, o.file, {o.area_samples, o.grid_resolution, o.seed}, &warning);
    if (!warning.empty()) std::fprintf(stderr, "pelage stats: %s\n", warning.c_str());
    if (!o.mesh.empty()) add_mask_adherence(o, pattern, &j);
    o.stats_json.write(j);
    if (o.json) {
        std::cout << j.dump(2) << std::endl;
    } else if (!o.quiet) {
        fmt::print("pelage stats: {}\n", o.file);
        fmt::print("  triangles {}  area {:.6g}  cells {}  {}\n", data.num_triangles(),
                   s.area, s.total_cells, by_type.dump());
        fmt::print("  spot fraction {:.4f} (by count)\n", s.spot_fraction);
        if (j.contains("stripe_alignment_median"))
            fmt::print(
                "  stripes against the anisotropy field: median {:.1f}° (quartiles "
                "{:.1f}°, {:.1f}°) over {} boundary cells, coherence {:.2f}\n",
                j["stripe_alignment_median"].get<double>(),
                j["stripe_alignment_q1"].get<double>(),
                j["stripe_alignment_q3"].get<double>(),
                j["stripe_alignment_samples"].get<size_t>(),
                j["stripe_coherence_median"].get<double>());
        if (j.contains("spot_fraction_by_area"))
            fmt::print("  by area ({} points): spot fraction {:.4f}  {}\n",
                       j["area_samples"].get<size_t>(),
                       j["spot_fraction_by_area"].get<double>(),
                       j["area_fraction_by_type"].dump());
        if (j.contains("mask_adherence"))
            for (const auto &m : j["mask_adherence"])
                fmt::print(
                    "  mask {} {} {}: {:.3f} of the surface masked out, {:.3f} % of it "
                    "shows {}\n",
                    m["type"].get<std::string>(),
                    m.contains("only_in") ? "only in" : "not in",
                    (m.contains("only_in") ? m["only_in"] : m["not_in"])
                        .get<std::string>(),
                    m["masked_out_share"].get<double>(),
                    100 * m["violation"].get<double>(), m["type"].get<std::string>());
        {
            fmt::print(
                "  spots {}  area mean {:.4g} sd {:.4g} ({:.3g} % of the surface "
                "each)  neighbours {:.2f}  circularity {:.3f}  complexity {:.3f}\n",
                j["spot_count"].get<size_t>(), j["spot_area_mean"].get<double>(),
                j["spot_area_sd"].get<double>(),
                100 * j["spot_area_share_mean"].get<double>(),
                j["spot_neighbours_mean"].get<double>(),
                j["spot_circularity_mean"].get<double>(),
                j["spot_complexity"].get<double>());
            fmt::print(
                "  background: {} components, largest {:.3f}, touching a spot "
                "{:.3f} (by area)\n",
                j["background_components"].get<size_t>(),
                j["background_largest_share"].get<double>(),
                j["background_near_spot"].get<double>());
        }
    }
    return 0;
}

}  // namespace

Runner add_stats_command(CLI::App &app) {
    auto o = std::make_shared<StatsOptions>();
    CLI::App *sub = app.add_subcommand("stats", "Pattern statistics of a .cells file");
    sub->add_option("file", o->file, ".cells file")->required();
    sub->add_flag("--json", o->json, "Print the JSON on stdout instead of text");
    sub->add_option("--mesh", o->mesh,
                    "The mesh the cells were grown on, or another of its shape (a "
                    "simplified copy's input), for the neural-crest masks' attributes "
                    "(mask_adherence); another shape is refused. Without it the "
                    "statistics are measured on the surface the file carries");
    sub->add_option("--preset", o->preset,
                    "With --mesh: the preset whose neural-crest masks to check "
                    "(mask_adherence; default: the preset stored in the file)");
    sub->add_option("--area-samples", o->area_samples,
                    "Surface points for the area fractions (standard error "
                    "sqrt(f(1-f)/n))")
        ->capture_default_str()
        ->check(CLI::Range(size_t(1000), size_t(100000000)));
    sub->add_option("--grid-resolution", o->grid_resolution,
                    "Grid steps per cell spacing for the spot statistics")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 64.0));
    refuse_pattern_seed(*sub, "--points-seed");
    sub->add_option("--points-seed", o->seed, "Seed of the random surface points")
        ->capture_default_str();
    o->stats_json.add_to(*sub, "the statistics");
    o->quiet.add_to(*sub);
    return [o] { return run_stats(*o); };
}

}  // namespace pelage::renderer::cli
