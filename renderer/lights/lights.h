// The scene's lights behind one closed dispatch (a switch on the type, no virtual calls):
// the environment, distant lights (a delta, or a disc of angular size, e.g. the sun),
// spheres and quads. Area lights are also Embree geometry
// (EmbreeScene::attach_area_lights): they occlude shadow rays and are found by camera and
// BSDF rays like any surface; their surface is black (it emits, it never reflects). A
// quad emits from its front side, towards edge_u × edge_v, unless `two_sided`; its back
// is black but still occludes. Radiometry: `color × intensity` is radiance for the
// environment, spheres and quads, and irradiance at normal incidence for distant lights.
// Light selection for next-event estimation (which leaves a constant environment to
// BSDF sampling, lights.cpp): every light at every vertex (select_pdf 1 each: the
// estimator and MIS treat each light as always chosen), the default for scenes of up to
// max_sample_all lights, where one shadow ray per light costs less than the
// variance of choosing (a sun and a sky chosen between are ~10× noisier than both
// sampled); or one light, in proportion to each light's estimated power (luminance of its
// flux into the scene's bounding sphere, pbrt-v4's Light::Phi), or uniformly;
// select_pdf(i) is the probability used in both the estimator and MIS.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/lights/light_environment.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

struct LightSample {
    Vec3f wi;        // unit, from the shading point towards the light
    Rgb Li;          // incident radiance
    float pdf;       // solid angle (1 for a delta light)
    float distance;  // to the light's surface; +inf for infinite lights
    bool delta;
};

class Lights {
  public:
    // scene_radius: the radius of the scene's bounding sphere (for infinite lights'
    // power).
    Lights(const std::vector<LightDesc> &descs, float scene_radius,
           IntegratorDesc::LightSelection selection);
    Lights(const Lights &) = delete;
    Lights &operator=(const Lights &) = delete;

    static constexpr int max_sample_all = 4;

    int count() const { return int(m_lights.size()); }
    // The lights next-event estimation samples: all but a constant environment.
    int nee_count() const { return m_nee_count; }
    // True when next-event estimation samples every light (select() is then unused).
    bool sample_all() const { return m_sample_all; }
    // The light next-event estimation uses for u in [0, 1) (nee_count() > 0), and its
    // probability: O(1)
    // by Walker's alias method (Vose 1991, "A Linear Algorithm for Generating Random
    // Numbers with a Given Distribution", IEEE TSE 17(9)): u picks a bin uniformly and
    // the rest of u chooses between the bin's own light and its alias.
    int select(float u, float *pdf) const {
        const int n = int(m_alias.size());
        const float x = u * float(n);
        const int bin = std::min(int(x), n - 1);
        const int i = x - float(bin) < m_alias[bin].keep ? bin : m_alias[bin].other;
        *pdf = m_select_pdf[i];
        return i;
    }
    float select_pdf(int index) const { return m_select_pdf[index]; }
    // Estimated power (luminance of the flux), for tests and statistics.
    float power(int index) const { return m_power[index]; }

    // Samples light `index` as seen from p, whose geometric normal n faces the side
    // being shaded. False when it cannot contribute. A constant environment is sampled
    // cosine-weighted about n (density cos θ / π), so no sample falls below the surface.
    bool sample(int index, const Vec3f &p, const Vec3f &n, float u1, float u2,
                LightSample *out) const;

    // Radiance leaving area light `index` towards -d where the ray (o, d) hits it at
    // distance t, and the solid-angle density with which sample() would have produced d
    // from o.
    Rgb area_radiance(int index, Vec3f o, Vec3f d, float t, float *pdf) const;

    // What an escaping ray sees: the environment plus distant discs containing d, each
    // with its radiance and the density with which sample() would have produced d (the
    // caller weights each with its own power-heuristic term).
    struct InfiniteHit {
        Rgb L;
        float pdf;  // sample()'s density, times the light's selection probability
    };
    // n_prev: the geometric normal at the vertex the ray left (for the constant
    // environment's density).
    int eval_infinite(Vec3f d, Vec3f n_prev, InfiniteHit out[], int max_out) const;

  private:
    void build_alias_table(const std::vector<double> &weights);

    struct Light {
        LightDesc::Type type;
        Rgb L;
        // distant
        Vec3f to_light;
        float cos_max = 1;
        float cone_pdf = 0;  // 1 / (2π (1 − cos_max)): the disc's uniform density
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
    std::vector<int> m_infinite;
    std::vector<float> m_power, m_select_pdf;
    struct AliasBin {
        float keep;  // probability that the bin selects its own light
        int other;   // the light it selects otherwise
    };
    std::vector<AliasBin> m_alias;  // one bin per light
    bool m_sample_all = false;
    int m_nee_count = 0;
};

}  // namespace pelage::renderer
