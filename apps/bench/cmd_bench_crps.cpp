// `pelage bench crps`: CRPS build time per triangle on a small and a large mesh (the
// build must be linear: the ratio of per-triangle costs should stay near 1),
// neighbour-map throughput (Teo §4.3: 4 mul + 4 add per point) and breadth-first
// unfolding cost.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "apps/bench/bench.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/crps/unfold.h"

namespace pelage::renderer::cli {
namespace {

struct BenchCrpsOptions {
    std::vector<std::string> meshes;
    int repeat = 3;
    ThreadOption threads;
    BenchOutput out;
};

nlohmann::json bench_one(const std::string &path, int repeat) {
    sim::MeshLoadReport report;
    const sim::TriangleMesh mesh = sim::load_mesh(path, &report);
    const size_t nt = mesh.num_triangles();

    // --- Build: topology + CRPS, best of `repeat` ---
    double best = 1e300, best_topo = 0, best_crps = 0;
    for (int r = 0; r < repeat; ++r) {
        const sim::Surface s = sim::build_surface(mesh);
        const double total = s.seconds_topology + s.seconds_crps;
        if (total < best) {
            best = total;
            best_topo = s.seconds_topology;
            best_crps = s.seconds_crps;
        }
    }
    const sim::Surface s = sim::build_surface(mesh);
    const sim::Crps &crps = s.crps;

    // --- Map throughput: apply every stored F[j→i] to j's first corner, until 0.2 s ---
    double sink = 0;
    size_t applied = 0;
    const Timer map_timer;
    do {
        for (sim::TriId i = 0; i < nt; ++i) {
            const auto nbrs = crps.topology().neighbours(i);
            const auto maps = crps.to_master(i);
            for (size_t k = 0; k < nbrs.size(); ++k) {
                const sim::Vec2d p = maps[k].apply(crps.frame(nbrs[k]).v[0]);
                sink += p.x + p.y;
            }
            applied += nbrs.size();
        }
    } while (map_timer.seconds() < 0.2);
    const double maps_per_second = applied / map_timer.seconds();

    // --- Unfolding within two mean edge lengths of each triangle (a sample of 4096) ---
    const double radius = 2.0 * sim::mean_edge_length(mesh, crps.topology());
    sim::UnfoldScratch scratch;
    std::vector<sim::UnfoldedTriangle> out;
    const size_t samples = std::min<size_t>(nt, 4096),
                 stride = std::max<size_t>(nt / samples, 1);
    size_t found = 0;
    const Timer unfold_timer;
    for (size_t n = 0; n < samples; ++n) {
        sim::unfold_around_triangle(crps, static_cast<sim::TriId>(n * stride % nt),
                                    radius, out, scratch);
        found += out.size();
    }
    const double unfold_ns = 1e9 * unfold_timer.seconds() / samples;

    return {{"mesh", path},
            {"triangles", nt},
            {"seconds", best},
            {"topology_seconds", best_topo},
            {"crps_seconds", best_crps},
            {"ns_per_triangle", 1e9 * best / nt},
            {"maps", crps.topology().nbr.size()},
            {"maps_per_second", maps_per_second},
            {"unfold_radius", radius},
            {"unfold_ns", unfold_ns},
            {"unfold_triangles_mean", double(found) / samples},
            {"checksum", sink}};
}

int run(const BenchCrpsOptions &o) {
    const auto control = o.threads.apply();
    std::vector<std::string> meshes = o.meshes;
    if (meshes.empty()) {
        meshes = {data_path("scenes/meshes/cow.off"),
                  data_path("scenes/meshes/bunny00.off")};
        for (const auto &m : meshes)
            if (!std::filesystem::exists(m))
                throw InputError(m, 0, "",
                                 "sample mesh missing: run scenes/fetch_meshes.sh "
                                 "(or pass --mesh)");
    }
    nlohmann::json runs = nlohmann::json::array();
    for (const auto &m : meshes) runs.push_back(bench_one(m, o.repeat));
    nlohmann::json j = {
        {"benchmark", "crps"}, {"threads", o.threads.threads}, {"runs", runs}};
    if (runs.size() >= 2) {
        // Linear build <=> per-triangle cost independent of size: the last (largest) run
        // over the first.
        j["ns_per_triangle_ratio"] = runs.back()["ns_per_triangle"].get<double>() /
                                     runs.front()["ns_per_triangle"].get<double>();
    }
    o.out.emit(j);
    return 0;
}

}  // namespace

Runner add_bench_crps(CLI::App &bench) {
    auto o = std::make_shared<BenchCrpsOptions>();
    CLI::App *sub = bench.add_subcommand(
        "crps", "CRPS build time per triangle, map throughput, unfolding");
    sub->add_option(
        "--mesh", o->meshes,
        "Meshes to measure, smallest first (default: the cow and bunny00 samples)");
    sub->add_option("--repeat", o->repeat, "Builds per mesh; the fastest counts")
        ->check(CLI::Range(1, 100));
    o->threads.add_to(*sub);
    o->out.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
