// The neighbour runs of `pelage bench sim`: which cells push a cell in the relaxation,
// and from how far, against exact geodesic distances (sim/geodesic, window propagation;
// itself held to CGAL's exact geodesics by the tests). Area-uniform cells at a preset's
// final density; the relaxation's checked unfoldings and Teo's first-path unfoldings
// (§4.1) side by side.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pelage::renderer::cli {

struct NeighbourOptions {
    std::vector<std::string> meshes;
    uint64_t cells = 8474;  // teo-leopard's final count
    double w_r = 3.3;       // and its repulsion weight
    size_t queries = 200;   // cells whose neighbours are compared
    uint64_t seed = 1;
};

// {"neighbours": [{mesh, cells, r, queries, pairs, checked: {missed_percent,
// through_folds, worst_error_r, mean_error_r}, first_path: {...}}]}. A pair goes through
// a fold when it pushes although the cells are more than 1.1 r apart on the surface, or
// its distance is short of theirs by more than 0.1 r; it is missed when the cells are
// within 0.9 r and it does not push.
nlohmann::json neighbour_runs(const NeighbourOptions &o);

}  // namespace pelage::renderer::cli
