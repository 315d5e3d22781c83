// `pelage bench lookup`: the clonal mosaic's closest-cell search (Teo 2006 §6.2) — ns per
// lookup (F1 and F2; F1 only) with Teo's pruning and without, candidate-list build time,
// and the crack rate along edges for both unfolding choices. Target: < 100 ns per lookup on the cow with
// 20 000 cells.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "renderer/cli/bench.h"
#include "shader/clonal_mosaic/closest_cell.h"
#include "shader/clonal_mosaic/edge_consistency.h"
#include "sim/input_error.h"
#include "sim/surface.h"
#include "sim/surface_sampling.h"

namespace pelage::cli {
namespace {

struct BenchLookupOptions {
    std::string mesh;
    size_t cells = 20000;
    size_t queries = 1000000;
    uint64_t seed = 1;
    ThreadOption threads;
};

int run(const BenchLookupOptions &o) {
    const auto control = o.threads.apply();
    const std::string mesh = o.mesh.empty() ? data_path("scenes/meshes/cow.off") : o.mesh;
    if (o.mesh.empty() && !std::filesystem::exists(mesh))
        throw InputError(mesh, 0, "", "sample mesh missing: run scenes/fetch_meshes.sh (or pass --mesh)");
    const sim::Surface s = sim::build_surface(mesh);

    // Area-uniform random cells stand in for a simulated mosaic: same density, and the
    // search does not care how the cells got there.
    std::vector<shader::CellOnSurface> list;
    uint32_t id = 0;
    for (const auto &p : sim::sample_surface_uniform(s.crps, o.cells, o.seed))
        list.push_back({p.tri, p.p.x, p.p.y, id++, uint8_t(id % 2)});
    const shader::CellTable cells = shader::make_cell_table(s.crps.num_triangles(), list);
    std::vector<std::pair<sim::TriId, shader::Vec2f>> queries;
    for (const auto &p : sim::sample_surface_uniform(s.crps, o.queries, o.seed + 1))
        queries.push_back({p.tri, {float(p.p.x), float(p.p.y)}});

    // A renderer's hits are coherent (neighbouring pixels, neighbouring triangles): the
    // same queries sorted by triangle measure that case; the random order is the worst.
    auto coherent = queries;
    std::stable_sort(coherent.begin(), coherent.end(),
                     [](const auto &a, const auto &b) { return a.first < b.first; });
    nlohmann::json modes = nlohmann::json::array();
    for (const auto paths : {sim::UnfoldPaths::edges_only, sim::UnfoldPaths::edges_and_vertices}) {
        const shader::ClosestCellIndex index(s.crps, cells, {paths});
        uint64_t sink = 0;
        const Timer pruned;
        for (const auto &[t, q] : queries) sink += index.find(t, q).index;
        const double ns = 1e9 * pruned.seconds() / queries.size();
        const Timer nearest;
        for (const auto &[t, q] : queries) sink += index.find_nearest(t, q).index;
        const double ns_f1 = 1e9 * nearest.seconds() / queries.size();
        const Timer sorted;
        for (const auto &[t, q] : coherent) sink += index.find(t, q).index;
        const double ns_coherent = 1e9 * sorted.seconds() / queries.size();
        const size_t n_ex = std::min<size_t>(queries.size(), 100000);
        const Timer exhaustive;
        for (size_t i = 0; i < n_ex; ++i) sink += index.find_exhaustive(queries[i].first, queries[i].second).index;
        const double ns_ex = 1e9 * exhaustive.seconds() / n_ex;
        const shader::EdgeConsistency edges = shader::measure_edge_consistency(s.mesh, s.crps, index);
        modes.push_back({{"unfolding", paths == sim::UnfoldPaths::edges_only ? "edges_only" : "edges_and_vertices"},
                         {"build_seconds", index.stats().build_seconds},
                         {"mean_candidates", index.stats().mean_candidates},
                         {"mean_candidate_cells", index.stats().mean_candidate_cells},
                         {"ns_per_lookup", ns},
                         {"ns_per_lookup_f1_only", ns_f1},
                         {"ns_per_lookup_coherent", ns_coherent},
                         {"ns_per_lookup_exhaustive", ns_ex},
                         {"pruning_speedup", ns_ex / ns},
                         {"edge_samples", edges.samples},
                         {"crack_rate", edges.crack_rate()},
                         {"inconsistent", edges.inconsistent},
                         {"checksum", sink}});
    }
    const nlohmann::json j = {{"benchmark", "lookup"},
                              {"mesh", mesh},
                              {"triangles", s.mesh.num_triangles()},
                              {"cells", cells.size()},
                              {"queries", queries.size()},
                              {"ns_per_lookup", modes[0]["ns_per_lookup"]},
                              {"modes", modes}};
    std::cout << j.dump(2) << std::endl;
    return 0;
}

}  // namespace

Runner add_bench_lookup(CLI::App &bench) {
    auto o = std::make_shared<BenchLookupOptions>();
    CLI::App *sub = bench.add_subcommand("lookup", "Closest-cell search: ns per lookup, pruning, cracks");
    sub->add_option("--mesh", o->mesh, "Mesh (default: the cow sample)");
    sub->add_option("--cells", o->cells, "Cells on the surface")->check(CLI::Range(size_t(1), size_t(100000000)));
    sub->add_option("--queries", o->queries, "Random surface points to look up")->check(CLI::Range(size_t(1), size_t(1000000000)));
    sub->add_option("--seed", o->seed, "Seed of the cells and queries");
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::cli
