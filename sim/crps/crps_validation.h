// Self-checks of a built CRPS, reported by `pelage crps` and asserted by the tests. All
// errors are relative to the mesh's bounding-box diagonal.
#pragma once

#include <cstdint>

#include "sim/crps/crps.h"

namespace pelage::sim {

struct CrpsValidation {
    double roundtrip_max_error =
        0;  // |to_3d(to_2d(p)) - p| over vertices + random points
    double barycentric_max_error =
        0;  // |to_3d(bary_to_2d(b)) - Σ b_k P_k|, and 2D -> bary -> 2D
    double edge_map_max_error = 0;     // shared edge endpoints after F[j→i]
    double edge_length_max_error = 0;  // lengths of j's edges after F[j→i] vs 3D lengths
    double vertex_map_max_error = 0;   // shared vertex after F[j→i], vertex neighbours
    double inverse_max_error = 0;      // F[i→j](F[j→i](p)) - p
    size_t maps_checked = 0;
};

CrpsValidation validate_crps(const TriangleMesh &mesh, const Crps &crps,
                             uint64_t seed = 1);

}  // namespace pelage::sim
