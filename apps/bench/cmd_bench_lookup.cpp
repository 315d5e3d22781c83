// `pelage bench lookup`: the clonal mosaic's closest-cell search (Teo 2006 §6.2) on the
// cow, the triceratops and the 760-triangle sphere — ns per lookup (F1+F2, F1 only,
// random and coherent query order; F1+F2 with the four-lane scans beside the eight-lane
// ones the CPU may have; banded walks across triangles, as camera hits, with
// and without CoherentLookup's reuse; the level of detail's filtered look, as wide
// indirect hits see it), agreement with the exhaustive search, the crack rate along
// edges, and, per mesh, the planar unfoldings beside the geodesic lists. Each also
// against exact geodesics (sim/geodesic, itself tested against CGAL's exact paths): the
// share of points given the geodesically nearest cell and its colour, the "impossible"
// answers (a distance shorter than the straight line to the returned cell) and the
// largest relative error of the returned cell's distance. Target: < 100 ns per lookup
// on the cow with 20 000 cells. Times are the thread's CPU time (ns_per_lookup_wall:
// wall clock).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "apps/bench/bench.h"
#include "apps/bench/bench_lookup_measure.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/crps/surface_sampling.h"
#include "sim/geodesic/windows_by_face.h"
#include "sim/mesh/subdivide.h"

namespace pelage::renderer::cli {
namespace {

struct BenchLookupOptions {
    std::vector<std::string> meshes;
    size_t cells = 20000;
    size_t queries = 1000000;
    uint64_t seed = 1;
    uint32_t subdivision = 3;
    int density_levels = 2;  // the first mesh split at its edge midpoints 1 … n times
    ThreadOption threads;
    BenchOutput out;
};

// Area-uniform random cells stand in for a simulated mosaic: same density, and the
// search does not care how the cells got there. Types alternate.
pattern::mosaic::CellTable random_cells(const sim::Crps &crps, size_t n, uint64_t seed) {
    std::vector<pattern::mosaic::CellOnSurface> list;
    uint32_t id = 0;
    for (const auto &p : sim::sample_surface_uniform(crps, n, seed)) {
        list.push_back({p.tri, p.p.x, p.p.y, id, uint8_t(id % 2)});
        ++id;
    }
    return pattern::mosaic::make_cell_table(crps.num_triangles(), list);
}

// The meshes to measure: the sample meshes unless --mesh names some.
std::vector<std::string> lookup_meshes(const BenchLookupOptions &o) {
    std::vector<std::string> meshes = o.meshes;
    if (meshes.empty()) {
        meshes = {data_path("scenes/meshes/cow.off"),
                  data_path("scenes/meshes/triceratops.off"), "procedural:sphere:20x20"};
        for (size_t i = 0; i < 2; ++i)
            if (!std::filesystem::exists(meshes[i]))
                throw InputError(
                    meshes[i], 0, "",
                    "sample mesh missing: run scenes/fetch_meshes.sh (or pass --mesh)");
    }
    return meshes;
}

// The reference: every cell's exact geodesic windows within four mean spacings (far
// beyond any point's nearest cell at these densities).
sim::WindowsByFace exact_reference(const sim::Surface &s,
                                   const pattern::mosaic::CellTable &cells) {
    std::vector<sim::SurfacePoint> sources(cells.size());
    for (sim::TriId t = 0; t < s.crps.num_triangles(); ++t)
        for (uint32_t k = cells.row[t]; k < cells.row[t + 1]; ++k)
            sources[k] = {t, {cells.x[k], cells.z[k]}};
    double area = 0;
    for (sim::TriId t = 0; t < s.crps.num_triangles(); ++t) area += s.crps.frame(t).area;
    const sim::GeodesicMesh geodesic_mesh(s.crps);
    sim::WindowsByFace exact;
    exact.build(geodesic_mesh, sources,
                4 * std::sqrt(area / double(std::max<size_t>(cells.size(), 1))));
    return exact;
}

// One mesh's run: the geodesic index's measurements, with the two unfoldings' beside.
nlohmann::json mesh_run(const std::string &mesh, const BenchLookupOptions &o) {
    const sim::Surface s = sim::build_surface(mesh);
    const pattern::mosaic::CellTable cells = random_cells(s.crps, o.cells, o.seed);
    std::vector<LookupQuery> queries;
    for (const auto &p : sim::sample_surface_uniform(s.crps, o.queries, o.seed + 1))
        queries.push_back({p.tri, {float(p.p.x), float(p.p.y)}});
    // A renderer's hits are coherent (neighbouring pixels hit neighbouring triangles):
    // the same queries sorted by triangle model that; random order is the worst case.
    std::vector<LookupQuery> coherent = queries;
    std::stable_sort(
        coherent.begin(), coherent.end(),
        [](const LookupQuery &a, const LookupQuery &b) { return a.first < b.first; });
    const sim::WindowsByFace exact = exact_reference(s, cells);
    using pattern::mosaic::Neighbourhood;
    nlohmann::json run = measure_lookups(s, cells, queries, coherent,
                                         Neighbourhood::geodesic, o.subdivision, exact);
    run["mesh"] = mesh;
    run["triangles"] = s.mesh.num_triangles();
    run["cells"] = cells.size();
    run["unfolding_edges"] =
        measure_lookups(s, cells, queries, coherent, Neighbourhood::unfolding_edges,
                        o.subdivision, exact);
    run["teo_unfolding"] = measure_lookups(
        s, cells, queries, coherent, Neighbourhood::unfolding_teo, o.subdivision, exact);
    return run;
}

// Density: the mesh split at its edge midpoints (the same surface, 4× the triangles
// each time), the same number of random cells: what the geodesic index costs per cell
// as triangles get small against the cells.
nlohmann::json density_runs(const std::string &first_mesh, const BenchLookupOptions &o) {
    nlohmann::json density = nlohmann::json::array();
    sim::TriangleMesh mesh = sim::build_surface(first_mesh).mesh;
    double base_ns = 0, base_build = 0, base_mb = 0;
    for (int level = 0; level <= o.density_levels; ++level) {
        if (level > 0) mesh = sim::subdivide(mesh, sim::Subdivision::midpoint);
        const sim::Surface s = sim::build_surface(mesh);
        const auto cells = random_cells(s.crps, o.cells, o.seed);
        const pattern::mosaic::ClosestCellIndex index(s.crps, cells);
        std::vector<LookupQuery> queries;
        for (const auto &p : sim::sample_surface_uniform(
                 s.crps, std::min<size_t>(o.queries, 200000), o.seed + 1))
            queries.push_back({p.tri, {float(p.p.x), float(p.p.y)}});
        uint64_t sink = 0;
        const CpuTimer timer;
        for (const auto &[t, q] : queries) sink += index.find_nearest(t, q).index;
        const double ns = 1e9 * timer.seconds() / double(queries.size());
        const auto &st = index.stats();
        if (level == 0) base_ns = ns, base_build = st.build_seconds, base_mb = st.bytes;
        density.push_back({{"subdivisions", level},
                           {"triangles", s.mesh.num_triangles()},
                           {"cells", cells.size()},
                           {"ns_per_lookup_f1_only", ns},
                           {"build_seconds", st.build_seconds},
                           {"index_megabytes", st.bytes / 1e6},
                           {"geodesic_windows", st.geodesic_windows},
                           {"geodesic_megabytes", st.geodesic_bytes / 1e6},
                           {"bent_entries", st.bent_entries},
                           {"ns_ratio", ns / base_ns},
                           {"build_ratio", st.build_seconds / base_build},
                           {"index_bytes_ratio", double(st.bytes) / base_mb},
                           {"checksum", sink}});
    }
    return density;
}

int run(const BenchLookupOptions &o) {
    const auto control = o.threads.apply();
    const std::vector<std::string> meshes = lookup_meshes(o);
    nlohmann::json runs = nlohmann::json::array();
    for (const std::string &mesh : meshes) runs.push_back(mesh_run(mesh, o));
    const nlohmann::json j = {{"benchmark", "lookup"},
                              {"queries", o.queries},
                              {"runs", runs},
                              {"density_mesh", meshes[0]},
                              {"density", density_runs(meshes[0], o)}};
    o.out.emit(j);
    return 0;
}

}  // namespace

Runner add_bench_lookup(CLI::App &bench) {
    auto o = std::make_shared<BenchLookupOptions>();
    CLI::App *sub = bench.add_subcommand(
        "lookup", "Closest-cell search: ns per lookup, pruning, cracks");
    sub->add_option("--mesh", o->meshes,
                    "Meshes (default: cow, triceratops, procedural:sphere:20x20)");
    sub->add_option("--cell-count", o->cells, "Cells on each surface")
        ->check(CLI::Range(size_t(1), size_t(100000000)));
    sub->add_option("--queries", o->queries, "Random surface points to look up")
        ->check(CLI::Range(size_t(1), size_t(1000000000)));
    sub->add_option("--points-seed", o->seed,
                    "Seed of the random cells and query points");
    refuse_pattern_seed(*sub, "--points-seed");
    sub->add_option("--subdivision", o->subdivision,
                    "Search regions per triangle side, at most (1-3)")
        ->check(CLI::Range(1, 3));
    sub->add_option("--density-levels", o->density_levels,
                    "Times the first mesh is split at its edge midpoints for the density "
                    "runs (0: none)")
        ->check(CLI::Range(0, 4));
    o->threads.add_to(*sub);
    o->out.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
