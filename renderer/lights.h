// The scene's lights behind one closed dispatch (a switch on the type, no virtual calls):
// the environment, distant lights (a delta, or a disc of angular size, e.g. the sun),
// spheres and quads. Area lights are not in the Embree scene: they neither occlude nor
// reflect; camera and BSDF rays test them analytically (a scene has few of them).
// Radiometry: `color × intensity` is radiance for the environment, spheres and quads, and
// irradiance at normal incidence for distant lights.
#pragma once

#include <memory>
#include <vector>

#include "renderer/light_environment.h"
#include "renderer/math.h"
#include "renderer/scene_file.h"

namespace pelage::renderer {

struct LightSample {
    Vec3f wi;        // unit, from the shading point towards the light
    Rgb Li;          // incident radiance
    float pdf;       // solid angle (1 for a delta light)
    float distance;  // to the light's surface; +inf for infinite lights
    bool delta;
};

struct AreaLightHit {
    int light = -1;
    float t = 0;
};

class Lights {
  public:
    explicit Lights(const std::vector<LightDesc> &descs);
    Lights(const Lights &) = delete;
    Lights &operator=(const Lights &) = delete;

    int count() const { return int(m_lights.size()); }
    float select_pdf() const { return m_lights.empty() ? 0.0f : 1.0f / m_lights.size(); }

    // Samples light `index` as seen from p, whose geometric normal n faces the side
    // being shaded. False when it cannot contribute. A constant environment is sampled
    // cosine-weighted about n (density cos θ / π), so no sample falls below the surface.
    bool sample(int index, Vec3f p, Vec3f n, float u1, float u2, LightSample *out) const;

    // Nearest area light along the ray closer than t_max.
    AreaLightHit intersect(Vec3f o, Vec3f d, float t_max) const;
    // Radiance leaving area light `index` towards -d at the hit, and the solid-angle
    // density with which sample() would have produced d from o.
    Rgb area_radiance(int index, Vec3f o, Vec3f d, float t, float *pdf) const;

    // What an escaping ray sees: the environment plus distant discs containing d, each
    // with its radiance and the density with which sample() would have produced d (the
    // caller weights each with its own power-heuristic term).
    struct InfiniteHit {
        Rgb L;
        float pdf;
    };
    // n_prev: the geometric normal at the vertex the ray left (for the constant
    // environment's density).
    int eval_infinite(Vec3f d, Vec3f n_prev, InfiniteHit out[], int max_out) const;

  private:
    struct Light {
        LightDesc::Type type;
        Rgb L;
        // distant
        Vec3f to_light;
        float cos_max = 1;
        Frame frame;
        // sphere
        Vec3f center;
        float radius = 0;
        // quad
        Vec3f corner, eu, ev, n;
        float area = 0;
        bool two_sided = false;
        // environment
        std::shared_ptr<EnvironmentLight> env;
    };
    std::vector<Light> m_lights;
    std::vector<int> m_area, m_infinite;
};

}  // namespace pelage::renderer
