#include "pattern/statistics/stats_report.h"

#include "pattern/statistics/area_fractions.h"
#include "pattern/statistics/spot_statistics.h"
#include "sim/cells_report/pattern_stats.h"
#include "sim/cells_report/stripe_alignment.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/anisotropy_field.h"
#include "sim/mosaic/preset.h"

namespace pelage::pattern::statistics {
namespace {

// The area keys: each type's share of the surface, and F / (F + B) by area (the
// count-based spot_fraction's definition, measured by area); then the spots.
void add_surface_statistics(const mosaic::MosaicPattern &pattern,
                            const StatsReportOptions &o, nlohmann::json *j) {
    const AreaFractions a = measure_area_fractions(pattern, o.area_samples, o.seed);
    nlohmann::json by_type = nlohmann::json::object();
    double f = 0, b = 0;
    for (size_t k = 0; k < a.by_type.size(); ++k) {
        const std::string &name = pattern.types()[k].name;
        by_type[name] = a.by_type[k];
        if (name == "F") f = a.by_type[k];
        if (name == "B") b = a.by_type[k];
    }
    (*j)["area_fraction_by_type"] = by_type;
    (*j)["spot_fraction_by_area"] = f + b > 0 ? f / (f + b) : 0.0;
    (*j)["area_samples"] = a.samples;

    const SpotStatistics l = measure_spot_statistics(pattern, o.grid_resolution);
    (*j)["spot_count"] = l.spots;
    (*j)["spot_area_mean"] = l.spot_area_mean;
    (*j)["spot_area_sd"] = l.spot_area_sd;
    (*j)["spot_area_share_mean"] = l.area > 0 ? l.spot_area_mean / l.area : 0.0;
    nlohmann::json quantiles = nlohmann::json::object();
    for (const auto &[name, q] : {std::pair{"min", 0.0},
                                  {"q10", 0.1},
                                  {"q25", 0.25},
                                  {"median", 0.5},
                                  {"q75", 0.75},
                                  {"q90", 0.9},
                                  {"max", 1.0}})
        quantiles[name] = spot_area_quantile(l, q);
    (*j)["spot_area_quantiles"] = quantiles;
    (*j)["largest_spot_cells"] = l.largest_spot_cells;
    (*j)["spot_neighbours_mean"] = l.spot_neighbours_mean;
    (*j)["spot_circularity_mean"] = l.spot_circularity_mean;
    (*j)["spot_complexity"] = l.spot_complexity;
    (*j)["background_components"] = l.background_components;
    (*j)["background_largest_share"] = l.background_largest_share;
    (*j)["background_near_spot"] = l.background_near_spot;
    (*j)["grid_resolution"] = o.grid_resolution;
}

// The stripe alignment keys when the cells were grown with anisotropy: the field is
// resolved again from the preset the file records, on the surface the file carries.
void add_stripe_alignment(const sim::CellsData &data, const sim::Surface &surface,
                          const std::string &file, nlohmann::json *j,
                          std::string *warning) {
    const nlohmann::json params = nlohmann::json::parse(data.params_json, nullptr, false);
    if (!params.is_object() || !params.contains("preset")) return;
    sim::Preset preset;
    try {
        preset = sim::parse_preset(params["preset"].dump(), file);
    } catch (const InputError &e) {
        // A file from a pelage that read presets otherwise: its other statistics stand.
        if (warning)
            *warning =
                std::string("no stripe alignment: the recorded preset: ") + e.what();
        return;
    }
    if (!(preset.params.w_a > 0)) return;
    const sim::TangentField field = sim::anisotropy_field(preset.params, surface.crps);
    const sim::StripeAlignment a =
        sim::measure_stripe_alignment(data, surface.crps, field);
    (*j)["stripe_alignment_median"] = a.median;
    (*j)["stripe_alignment_q1"] = a.q1;
    (*j)["stripe_alignment_q3"] = a.q3;
    (*j)["stripe_alignment_samples"] = a.samples;
    (*j)["stripe_coherence_median"] = a.coherence;
}

}  // namespace

nlohmann::json stats_report(const mosaic::MosaicPattern &pattern, const std::string &file,
                            const StatsReportOptions &options, std::string *warning) {
    const sim::CellsData &data = pattern.data();
    const sim::PatternStats s = sim::compute_pattern_stats(data);
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto &[name, n] : s.cells_by_type) by_type[name] = n;
    nlohmann::json j = {
        {"file", file},
        {"triangles", data.num_triangles()},
        {"area", s.area},
        {"cells", s.total_cells},
        {"cells_by_type", by_type},
        {"spot_fraction", s.spot_fraction},
    };
    add_surface_statistics(pattern, options, &j);
    add_stripe_alignment(data, pattern.surface(), file, &j, warning);
    return j;
}

}  // namespace pelage::pattern::statistics
