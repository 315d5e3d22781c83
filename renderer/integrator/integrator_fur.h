// A path vertex on a fur strand: the Chiang et al. 2016 hair BSDF (renderer/bsdf) with
// next-event estimation and MIS like any surface vertex, in the fibre's frame
// (x along the strand's tangent, z the tube's normal at the hit, facing the ray).
//
// Unlike a surface the fibre is transmissive: light and continuation directions on
// either side of z are valid. A constant environment is light-sampled over z's
// hemisphere only (lights.h samples it about the normal it is given) and the vertex
// hands z on as the path's previous normal, so the BSDF-sampled side of the MIS pair
// uses the same density and the estimator stays unbiased; the far hemisphere is reached
// by BSDF sampling alone. Rays leaving the strand carry its id so they skip it
// (fur_geometry.h).
#pragma once

#include "renderer/bsdf/hair_bsdf.h"
#include "renderer/integrator/integrator_path.h"

namespace pelage::renderer {

// The fibre frame: x the tangent, z ⊥ x facing wo, y = z × x.
struct FibreFrame {
    Vec3f x, y, z;
    Vec3f to_local(Vec3f v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
    Vec3f to_world(Vec3f v) const { return x * v.x + y * v.y + z * v.z; }
};

struct PathIntegrator::StrandVertex {
    const FurLayer &layer;
    uint32_t strand;  // within the layer
    Vec3f p, wo;
    float t_hit;
    FibreFrame frame;
    HairBsdf bsdf;  // from the strand's melanin, at the hit's offset h across the fibre
};

}  // namespace pelage::renderer
