#include "sim/crps/surface.h"

#include <chrono>

namespace pelage::sim {
namespace {

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Surface assemble(TriangleMesh mesh, MeshLoadReport load, double seconds_load) {
    auto t0 = std::chrono::steady_clock::now();
    Topology topo = build_topology(mesh);
    const double seconds_topology = since(t0);
    t0 = std::chrono::steady_clock::now();
    Crps crps(mesh, std::move(topo));
    const double seconds_crps = since(t0);
    return Surface{std::move(mesh), std::move(crps),  load,
                   seconds_load,    seconds_topology, seconds_crps};
}

}  // namespace

Surface build_surface(const std::string &path_or_spec) {
    const auto t0 = std::chrono::steady_clock::now();
    MeshLoadReport load;
    TriangleMesh mesh = load_mesh(path_or_spec, &load);
    return assemble(std::move(mesh), load, since(t0));
}

Surface build_surface(TriangleMesh mesh) { return assemble(std::move(mesh), {}, 0.0); }

}  // namespace pelage::sim
