#include "sim/mosaic/anisotropy_field.h"

namespace pelage::sim {

TangentField anisotropy_field(const SimParams &params, const Crps &crps) {
    if (!(params.w_a > 0)) return {};
    if (params.anisotropy_field.kind != FieldSpec::Kind::none)
        return resolve_field(params.anisotropy_field, crps, params.anisotropy_magnitude);
    return constant_world_field(crps, params.anisotropy_direction,
                                params.anisotropy_magnitude);
}

}  // namespace pelage::sim
