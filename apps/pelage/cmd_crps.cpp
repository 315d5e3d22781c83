// `pelage crps --mesh FILE`: builds the CRPS of a mesh and prints its summary and
// self-validation (keys of --stats-json are a contract).
#include <fmt/core.h>

#include <cstdio>

#include "apps/common/common.h"
#include "sim/crps/crps_validation.h"
#include "sim/crps/surface.h"

namespace pelage::renderer::cli {
namespace {

struct CrpsOptions {
    std::string mesh;
    uint64_t seed = 1;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

// The human-readable summary: the mesh as loaded, its CRPS, and the self-validation.
void print_summary(const std::string &mesh, const sim::Surface &s,
                   const sim::CrpsValidation &v, size_t primary, size_t secondary,
                   double area, double mel, double diag) {
    const sim::Topology &topo = s.crps.topology();
    const double build_seconds = s.seconds_topology + s.seconds_crps;
    fmt::print("pelage crps: {}\n", mesh);
    fmt::print("  triangles          {:>10}   (read {}, degenerate dropped {})\n",
               s.mesh.num_triangles(), s.load.raw_triangles,
               s.load.clean.degenerate_dropped);
    fmt::print(
        "  vertices           {:>10}   (read {}, welded {}, stitched {}, unused {})\n",
        s.mesh.num_vertices(), s.load.raw_vertices, s.load.clean.vertices_welded,
        s.load.clean.vertices_stitched, s.load.clean.unused_vertices);
    fmt::print(
        "  edges              {:>10}   (boundary {}, non-manifold {}, non-orientable "
        "{})\n",
        topo.num_edges(), topo.boundary_edges, topo.nonmanifold_edges,
        topo.nonorientable_edges);
    fmt::print(
        "  components         {:>10}   (faces reoriented {}, non-manifold vertices {})\n",
        topo.num_components, topo.faces_reoriented, topo.nonmanifold_vertices);
    fmt::print(
        "  neighbour maps     {:>10}   (primary {}, secondary {}; {:.1f} per triangle)\n",
        topo.nbr.size(), primary, secondary,
        double(topo.nbr.size()) / s.mesh.num_triangles());
    fmt::print("  surface area       {:>10.6g}\n", area);
    fmt::print("  mean edge length   {:>10.6g}   (bounding-box diagonal {:.6g})\n", mel,
               diag);
    fmt::print(
        "  build time         {:>10.3f} ms (load {:.3f} ms, topology {:.3f} ms, CRPS "
        "{:.3f} ms)\n",
        1e3 * build_seconds, 1e3 * s.seconds_load, 1e3 * s.seconds_topology,
        1e3 * s.seconds_crps);
    fmt::print("  validation, max error relative to the diagonal, over {} maps:\n",
               v.maps_checked);
    fmt::print("    2D <-> 3D round trip       {:.3g}\n", v.roundtrip_max_error);
    fmt::print("    barycentric <-> 2D         {:.3g}\n", v.barycentric_max_error);
    fmt::print("    edge maps (shared ends)    {:.3g}\n", v.edge_map_max_error);
    fmt::print("    vertex maps (shared vertex){:.3g}\n", v.vertex_map_max_error);
    fmt::print("    edge lengths after maps    {:.3g}\n", v.edge_length_max_error);
    fmt::print("    F[i->j] o F[j->i] - I      {:.3g}\n", v.inverse_max_error);
}

int run_crps(const CrpsOptions &o) {
    const auto control = o.threads.apply();
    const Timer timer;
    const sim::Surface s = sim::build_surface(o.mesh);
    const double build_seconds = s.seconds_topology + s.seconds_crps;
    const double total_seconds = timer.seconds();
    const sim::CrpsValidation v = sim::validate_crps(s.mesh, s.crps, o.seed);
    const sim::Topology &topo = s.crps.topology();

    size_t primary = 0;
    for (uint8_t n : topo.num_primary) primary += n;
    const size_t secondary = topo.nbr.size() - primary;
    const double area = s.mesh.surface_area();
    const double mel = sim::mean_edge_length(s.mesh, topo);
    const double diag = s.mesh.bounds().diagonal();

    if (!o.quiet) print_summary(o.mesh, s, v, primary, secondary, area, mel, diag);
    if (o.stats_json.wanted()) {
        nlohmann::json j = {
            {"mesh", o.mesh},
            {"triangles", s.mesh.num_triangles()},
            {"vertices", s.mesh.num_vertices()},
            {"edges", topo.num_edges()},
            {"boundary_edges", topo.boundary_edges},
            {"nonmanifold_edges", topo.nonmanifold_edges},
            {"nonorientable_edges", topo.nonorientable_edges},
            {"nonmanifold_vertices", topo.nonmanifold_vertices},
            {"components", topo.num_components},
            {"faces_reoriented", topo.faces_reoriented},
            {"degenerate_dropped", s.load.clean.degenerate_dropped},
            {"vertices_welded", s.load.clean.vertices_welded},
            {"vertices_stitched", s.load.clean.vertices_stitched},
            {"polygons_triangulated", s.load.read.polygons_triangulated},
            {"primary_maps", primary},
            {"secondary_maps", secondary},
            {"area", area},
            {"mean_edge_length", mel},
            {"bbox_diagonal", diag},
            {"roundtrip_max_error", v.roundtrip_max_error},
            {"barycentric_max_error", v.barycentric_max_error},
            {"edge_map_max_error", v.edge_map_max_error},
            {"vertex_map_max_error", v.vertex_map_max_error},
            {"edge_length_max_error", v.edge_length_max_error},
            {"inverse_max_error", v.inverse_max_error},
            {"seconds", build_seconds},
            {"seconds_load", s.seconds_load},
            {"seconds_total", total_seconds},
        };
        o.stats_json.write(j);
    }
    return 0;
}

}  // namespace

Runner add_crps_command(CLI::App &app) {
    auto o = std::make_shared<CrpsOptions>();
    CLI::App *sub = app.add_subcommand(
        "crps",
        "Build the Canonical Reference Plane Structure of a mesh and validate it");
    sub->add_option(
           "--mesh", o->mesh,
           "Mesh file (.off, .obj, .gltf, .glb, .fbx, .ply, .dae, ...), FILE#NAME for "
           "one named object of it, or procedural:sphere:20x20 ...")
        ->required();
    o->stats_json.add_to(*sub, "the summary");
    o->quiet.add_to(*sub);
    sub->add_option("--points-seed", o->seed, "Seed of the random validation points");
    refuse_pattern_seed(*sub, "--points-seed");
    o->threads.add_to(*sub);
    return [o] { return run_crps(*o); };
}

}  // namespace pelage::renderer::cli
