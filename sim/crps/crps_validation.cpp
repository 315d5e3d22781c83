#include "sim/crps/crps_validation.h"

#include <algorithm>
#include <random>

namespace pelage::sim {

CrpsValidation validate_crps(const TriangleMesh &mesh, const Crps &crps, uint64_t seed) {
    CrpsValidation v;
    const double diag = mesh.bounds().diagonal();
    const double inv_diag = diag > 0 ? 1.0 / diag : 1.0;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    auto grow = [&](double &worst, double err) {
        worst = std::max(worst, err * inv_diag);
    };

    for (TriId t = 0; t < mesh.num_triangles(); ++t) {
        // --- 2D <-> 3D round trip on the corners and on random interior points ---
        const Vec3d P[3] = {mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2)};
        for (int c = 0; c < 3; ++c)
            grow(v.roundtrip_max_error,
                 length(crps.to_3d(t, crps.to_2d(t, P[c])) - P[c]));
        for (int s = 0; s < 4; ++s) {
            double b1 = u01(rng), b2 = u01(rng);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            const Vec3d b{1 - b1 - b2, b1, b2};
            const Vec3d p = P[0] * b.x + P[1] * b.y + P[2] * b.z;
            const Vec2d q = crps.barycentric_to_2d(t, b);
            grow(v.roundtrip_max_error, length(crps.to_3d(t, crps.to_2d(t, p)) - p));
            grow(v.barycentric_max_error, length(crps.to_3d(t, q) - p));
            const Vec3d b_back = crps.to_barycentric(t, q);
            grow(v.barycentric_max_error, length(crps.barycentric_to_2d(t, b_back) - q));
        }

        // --- Neighbour maps: shared corners coincide, lengths kept, inverse undoes ---
        const auto nbrs = crps.topology().neighbours(t);
        const auto to_master = crps.to_master(t), to_nbr = crps.to_neighbour(t);
        for (size_t k = 0; k < nbrs.size(); ++k) {
            const TriId j = nbrs[k];
            const RigidMap2 &F = to_master[k];
            const CrpsFrame &fi = crps.frame(t), &fj = crps.frame(j);
            int shared = 0;
            for (int cj = 0; cj < 3; ++cj) {
                const Vec2d mapped = F.apply(fj.v[cj]);
                grow(v.inverse_max_error, length(to_nbr[k].apply(mapped) - fj.v[cj]));
                for (int ci = 0; ci < 3; ++ci)
                    if (mesh.triangles[t][ci] == mesh.triangles[j][cj]) {
                        ++shared;
                        const double err = length(mapped - fi.v[ci]);
                        grow(k < crps.topology().num_primary[t] ? v.edge_map_max_error
                                                                : v.vertex_map_max_error,
                             err);
                    }
                const int cn = (cj + 1) % 3;
                const double len3 = length(mesh.vertex(j, cn) - mesh.vertex(j, cj));
                const double len2 = length(F.apply(fj.v[cn]) - mapped);
                grow(v.edge_length_max_error, std::abs(len3 - len2));
            }
            ++v.maps_checked;
        }
    }
    return v;
}

}  // namespace pelage::sim
