// A path vertex on a fur strand: the Chiang et al. 2016 hair BSDF (shader/hair) with
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

#include "renderer/integrator/integrator_path.h"

namespace pelage::renderer {

// The path state a strand vertex reads and updates.
struct FurPathState {
    Rgb &L, &beta;
    Vec3f &o, &d;
    float &prev_pdf;
    bool &prev_specular;
    Vec3f &prev_ng;
    unsigned &skip_id;  // the next ray's id (fur_geometry.h)
};

// Shades the hit `rh` on `layer` at path vertex `depth`: sets the film's first-hit values
// at depth 0, adds direct light and samples the continuation (unless `last`). Returns
// false when the path ends here. `instr`: NoInstrumentation or Instrumented.
template <typename Instr>
bool scatter_at_strand(const Scene &scene, const FurLayer &layer, const RTCRayHit &rh,
                       int depth, bool last, Sampler &sampler, FurPathState &st,
                       FilmSample &fs, FilmPointAovs *aovs, const CameraRay &cam,
                       RenderStats &stats, const Instr &instr);

}  // namespace pelage::renderer
