#include "apps/bench/bench_lookup_measure.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "apps/common/common.h"
#include "pattern/mosaic/coherent_lookup.h"
#include "pattern/mosaic/edge_consistency.h"
#include "pattern/mosaic/mosaic_lod.h"

namespace pelage::renderer::cli {
namespace {

// What the timed steps share: the search under test, its queries, and a checksum of
// the cells found, which keeps every timed search from being optimised away (each step
// sums into a local, kept in a register in its loops, and adds it here).
struct LookupBench {
    const sim::Surface &s;
    const pattern::mosaic::CellTable &cells;
    const pattern::mosaic::ClosestCellIndex &index;
    const std::vector<LookupQuery> &queries;
    const std::vector<LookupQuery> &coherent;
    uint64_t sink = 0;
};

// Against exact geodesics: the first 20 000 queries.
nlohmann::json geodesic_agreement(const LookupBench &b, const sim::WindowsByFace &exact) {
    const sim::Surface &s = b.s;
    const pattern::mosaic::CellTable &cells = b.cells;
    size_t compared = 0, same = 0, same_colour = 0, impossible = 0;
    double worst = 0;
    for (size_t i = 0; i < std::min<size_t>(b.queries.size(), 20000); ++i) {
        const auto &[t, q] = b.queries[i];
        const sim::Vec2d qd{q.x, q.y};
        const sim::WindowsByFace::Nearest truth = exact.nearest(t, qd);
        const pattern::mosaic::ClosestCell c = b.index.find_nearest(t, q);
        if (truth.source == sim::invalid_id ||
            c.index == pattern::mosaic::ClosestCell::none)
            continue;
        ++compared;
        same += c.index == truth.source;
        same_colour += cells.type[c.index] == cells.type[truth.source];
        sim::TriId ct = 0;
        while (cells.row[ct + 1] <= c.index) ++ct;
        const sim::Vec3d cell = s.crps.to_3d(ct, {cells.x[c.index], cells.z[c.index]});
        impossible += c.f1 < length(s.crps.to_3d(t, qd) - cell) * (1 - 1e-5);
        const double d = exact.distance(t, qd, c.index);
        if (std::isfinite(d) && d > 0) worst = std::max(worst, std::abs(c.f1 - d) / d);
    }
    const double n_compared = double(std::max<size_t>(compared, 1));
    return {{"geodesic_points", compared},
            {"geodesic_same_cell", same / n_compared},
            {"geodesic_same_colour", same_colour / n_compared},
            {"geodesic_impossible", impossible / n_compared},
            {"geodesic_distance_error_max", worst}};
}

// F1+F2 in random order (CPU and wall time), with the four-lane scans (lane_scan.h)
// beside the index's own, F1 only, and F1+F2 in coherent order, into out. Returns the
// ns per F1+F2 lookup in random order.
double time_point_lookups(LookupBench &b, pattern::mosaic::ClosestCellOptions options,
                          nlohmann::json &out) {
    const pattern::mosaic::ClosestCellIndex &index = b.index;
    const std::vector<LookupQuery> &queries = b.queries;
    uint64_t sink = 0;
    const Timer wall;
    const CpuTimer pruned;
    for (const auto &[t, q] : queries) sink += index.find(t, q).index;
    const double ns = 1e9 * pruned.seconds() / queries.size();
    const double ns_wall = 1e9 * wall.seconds() / queries.size();
    out["ns_per_lookup"] = ns;
    out["ns_per_lookup_wall"] = ns_wall;
    // The same lookups with the four-lane scans: their time, and that they find the
    // same cells.
    options.wide_lanes = false;
    const pattern::mosaic::ClosestCellIndex narrow(b.s.crps, b.cells, options);
    uint64_t wide_sink = 0, narrow_sink = 0;
    for (const auto &[t, q] : queries) wide_sink += index.find(t, q).index;
    const CpuTimer four_lanes;
    for (const auto &[t, q] : queries) narrow_sink += narrow.find(t, q).index;
    out["ns_per_lookup_four_lanes"] = 1e9 * four_lanes.seconds() / queries.size();
    out["lanes_agree"] = wide_sink == narrow_sink;
    const CpuTimer nearest;
    for (const auto &[t, q] : queries) sink += index.find_nearest(t, q).index;
    out["ns_per_lookup_f1_only"] = 1e9 * nearest.seconds() / queries.size();
    const CpuTimer sorted;
    for (const auto &[t, q] : b.coherent) sink += index.find(t, q).index;
    out["ns_per_lookup_coherent"] = 1e9 * sorted.seconds() / queries.size();
    b.sink += sink;
    return ns;
}

// The material's soft-edge search (antialiased camera hits): the cells within F1 +
// band, band a tenth of the mean cell spacing, in coherent order; then camera hits as
// the material sees them: walks of 32 steps across each triangle (as neighbouring
// pixels along a row), banded, searched every time and through CoherentLookup (the
// plugin's camera path), which reuses a proven cell.
void time_banded_lookups(LookupBench &b, nlohmann::json &out) {
    const sim::Surface &s = b.s;
    const pattern::mosaic::ClosestCellIndex &index = b.index;
    double area = 0;
    for (sim::TriId t = 0; t < s.crps.num_triangles(); ++t) area += s.crps.frame(t).area;
    const float band =
        float(0.1 * std::sqrt(area / double(std::max<size_t>(b.cells.size(), 1))));
    uint64_t sink = 0;
    const CpuTimer banded;
    for (const auto &[t, q] : b.coherent)
        sink += index.find_three_within(t, q, band).index[1];
    out["ns_per_lookup_banded_coherent"] = 1e9 * banded.seconds() / b.queries.size();
    struct Step {
        sim::TriId t;
        float b1, b2;
    };
    std::vector<Step> walk;
    for (sim::TriId t = 0; t < s.crps.num_triangles() && walk.size() < b.queries.size();
         ++t)
        for (int k = 0; k < 32; ++k) {
            const float u = (k + 0.5f) / 32;
            walk.push_back({t, 0.7f * u, 0.25f * u + 0.2f * u * (1 - u)});
        }
    const CpuTimer walked;
    for (const Step &w : walk)
        sink += index.find_three_within(w.t, w.b1, w.b2, band).index[1];
    out["ns_per_lookup_banded_walk"] = 1e9 * walked.seconds() / walk.size();
    pattern::mosaic::CoherentLookup reuse;
    const CpuTimer reused;
    for (const Step &w : walk)
        sink += reuse.find_three_within(index, 1, w.t, w.b1, w.b2, band).index[1];
    out["ns_per_lookup_banded_walk_reuse"] = 1e9 * reused.seconds() / walk.size();
    out["walk_reused"] =
        double(reuse.reused()) / double(std::max<size_t>(walk.size(), 1));
    b.sink += sink;
}

// Indirect hits with wide footprints (the material's level of detail): the filtered
// look at random points, in random order. Its values stay out of the checksum, which
// compares searches.
double time_filtered_looks(const LookupBench &b) {
    const std::vector<LookupQuery> &queries = b.queries;
    const pattern::mosaic::MosaicLod lod(
        b.s, b.index,
        [&](uint32_t c) {
            const float v = float(b.cells.type[c]);
            return pattern::mosaic::FilteredLook{{v, 1 - v, 0.5f * v, v, 1 - v}};
        },
        2);
    std::vector<std::array<float, 2>> bary;  // hits come with barycentrics
    for (const auto &[t, q] : queries) {
        const sim::Vec3d bc = b.s.crps.to_barycentric(t, {q.x, q.y});
        bary.push_back({float(bc.y), float(bc.z)});
    }
    float lod_sink = 0;
    const CpuTimer filtered;
    for (size_t i = 0; i < queries.size(); ++i) {
        const sim::TriId t = queries[i].first;
        lod_sink += lod.weight(t, 1e30f) * lod.at(t, bary[i][0], bary[i][1]).v[0];
    }
    const double ns_lod = 1e9 * filtered.seconds() / queries.size();
    volatile float keep = lod_sink;
    (void)keep;
    return ns_lod;
}

// The exhaustive search on the first 100 000 queries: its time beyond the pruned
// search's (ns_pruned, called beside it), and how often the two agree.
void time_exhaustive(const LookupBench &b, double ns_pruned, nlohmann::json &out) {
    const std::vector<LookupQuery> &queries = b.queries;
    const size_t n_ex = std::min<size_t>(queries.size(), 100000);
    size_t agree = 0;
    const CpuTimer exhaustive;
    for (size_t i = 0; i < n_ex; ++i) {
        const pattern::mosaic::ClosestCell x =
            b.index.find_exhaustive(queries[i].first, queries[i].second);
        const pattern::mosaic::ClosestCell y =
            b.index.find(queries[i].first, queries[i].second);
        agree += x.index == y.index && x.f2 == y.f2;
    }
    out["ns_per_lookup_exhaustive"] = 1e9 * exhaustive.seconds() / n_ex - ns_pruned;
    out["exhaustive_agreement"] = double(agree) / n_ex;
}

const char *neighbourhood_name(pattern::mosaic::Neighbourhood neighbourhood) {
    using pattern::mosaic::Neighbourhood;
    return neighbourhood == Neighbourhood::geodesic          ? "geodesic"
           : neighbourhood == Neighbourhood::unfolding_edges ? "unfolding_edges"
                                                             : "unfolding_teo";
}

}  // namespace

nlohmann::json measure_lookups(const sim::Surface &s,
                               const pattern::mosaic::CellTable &cells,
                               const std::vector<LookupQuery> &queries,
                               const std::vector<LookupQuery> &coherent,
                               pattern::mosaic::Neighbourhood neighbourhood,
                               uint32_t subdivision, const sim::WindowsByFace &exact) {
    const pattern::mosaic::ClosestCellIndex index(s.crps, cells,
                                                  {neighbourhood, subdivision});
    LookupBench b{s, cells, index, queries, coherent};
    nlohmann::json out = geodesic_agreement(b, exact);
    const double ns = time_point_lookups(b, {neighbourhood, subdivision}, out);
    time_banded_lookups(b, out);
    out["ns_per_lookup_lod"] = time_filtered_looks(b);
    time_exhaustive(b, ns, out);
    const pattern::mosaic::EdgeConsistency edges =
        pattern::mosaic::measure_edge_consistency(s.mesh, s.crps, index);
    const auto &stats = index.stats();
    out.update({{"neighbourhood", neighbourhood_name(neighbourhood)},
                {"build_seconds", stats.build_seconds},
                {"mean_candidates", stats.mean_candidates},
                {"mean_candidate_cells", stats.mean_candidate_cells},
                {"fine_regions", stats.fine_regions},
                {"index_megabytes", stats.bytes / 1e6},
                {"triangles_with_regions", stats.triangles_with_regions},
                {"lanes", stats.lanes},
                {"edge_samples", edges.samples},
                {"edge_disagreement", edges.crack_rate()},
                {"edge_inconsistent", edges.inconsistent},
                {"geodesic_radius", stats.geodesic_radius},
                {"bent_entries", stats.bent_entries},
                {"checksum", b.sink}});
    return out;
}

}  // namespace pelage::renderer::cli
