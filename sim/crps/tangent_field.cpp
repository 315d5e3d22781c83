#include "sim/crps/tangent_field.h"

namespace pelage::sim {

TangentField constant_world_field(const Crps &crps, std::array<double, 3> direction,
                                  double magnitude) {
    TangentField field;
    field.a.resize(crps.num_triangles());
    const Vec3d dir{direction[0], direction[1], direction[2]};
    for (TriId t = 0; t < crps.num_triangles(); ++t) {
        // In the canonical frame the normal is +Y, so dropping Y projects onto the face.
        const Vec3d c = crps.frame(t).rotation * dir;
        const Vec2d p{c.x, c.z};
        const double len = length(p);
        // Below ~1e-6 the face is perpendicular to the direction: no preferred axis.
        field.a[t] = len > 1e-6 ? p * (magnitude / len) : Vec2d{};
    }
    return field;
}

}  // namespace pelage::sim
