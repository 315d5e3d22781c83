// Fur in the Embree scene: for every object with a `"fur"` block, renderer/fur grows its
// strands on the object's world-space mesh, each taking its pigment from the object's
// own material plugin at the root (so fur follows whatever pattern the skin shows, in
// the colours it shows), and the strands become one Embree curve geometry in the scene's
// top level:
// RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE (tubes, close-ups) or FLAT_LINEAR_CURVE
// (ray-facing ribbons, distance). Control points are shared with Embree as FLOAT4
// (x, y, z, radius), 16 bytes each; per strand the renderer keeps only its absorption
// σ_a (12 bytes).
//
// Self-intersection: a ray leaving a strand carries (global strand index + 1) in its
// `id`; the curves' filter function rejects hits on that strand, so transmitted (TT)
// paths pass through their own fibre as the hair BSDF assumes. Other rays carry id 0.
// Round curves also drop every hit on the inside of a tube. Strands whose roots lie
// closer than the sum of their radii interpenetrate (with density ρ and root radius r,
// a fraction 1 − exp(−4πρr²) of them: 47 % at ρ = 200 000, r = 0.0005), and a ray
// leaving one of them inside another would hit that one's inner wall, where the hair
// BSDF (a whole fibre, entered from outside) means nothing: bounces were scattered there
// again and shadow rays blocked, which darkened dense fur (Cycles culls these hits on
// its round curves too). Flat ribbons have no inside.
//
// Strands thinner on screen than `min_pixel_width` pixels (FurParams) are widened to it,
// and their opacity scaled by own radius / widened radius, so each strand covers on
// average what it covered before (Arnold's min_pixel_width, Cycles' former minimum
// width; Cook, Halstead, Planck & Ryu 2007, "Stochastic simplification of aggregate
// detail", widen what they thin for the same reason). The widening is geometry, built
// for the camera the scene is built for (pixel angle × distance); the opacity is
// stochastic in the filter function, for camera rays: a hit is kept when a stratified
// number ξ of the pixel's sampler (in the ray's id), rotated by a hash of the strand
// (Cranley–Patterson), falls below it, so a sub-pixel strand covers close to its share
// of the pixel's samples instead of a binomial draw of them. The widened strands are
// ribbons facing the ray (a camera ray meets one where it passes the centre line, so the
// nearest kept strand is the one whose fibre is nearest) in a scene of their own, the
// camera scene, with everything else in the scene; shadow and bounce rays, which the
// widening is not for, see the fibres themselves, as without widening, and pay nothing
// for it. A path leaves a widened strand from its fibre, not from the widened surface.
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/fur/fur_grow.h"
#include "renderer/geometry/embree_scene.h"
#include "renderer/scene_file/scene_file.h"

namespace pelage::renderer {

// A ray's Embree id: the global index + 1 of the strand it leaves in bits 0–25 (0: none),
// and for a camera ray a stratified number ξ in [0, 1) quantised to 32 levels in bits
// 26–30, with bit 31 saying that it is there.
inline constexpr unsigned fur_skip_bits = 26;
inline constexpr unsigned fur_skip_mask = (1u << fur_skip_bits) - 1;
inline unsigned fur_ray_id(unsigned skip, float xi) {
    const unsigned q = std::min(31u, unsigned(std::max(xi, 0.0f) * 32));
    return skip | q << fur_skip_bits | 1u << 31;
}

// A root's pigment on object `object`: the skin's material evaluated at that point.
using ObjectPigmentLookup =
    std::function<RootPigment(size_t object, const SurfacePoint &, Vec3f p, Vec3f n)>;

struct FurLayer {
    uint32_t object = 0;  // the scene object the fur grows on
    // The fibres in the scene; the widened strands, when there are, in the camera scene.
    unsigned geom_id = RTC_INVALID_GEOMETRY_ID;
    uint32_t strand_offset = 0;  // global index of this layer's first strand
    bool round = true;
    float beta_m = 0.25f, beta_n = 0.3f, alpha = 0;  // alpha in radians
    Strands strands;

    // Strand s's longitudinal and azimuthal roughness: its own when the groom varies
    // them (Strands::beta), else the layer's.
    float beta_m_of(uint32_t s) const {
        return strands.beta.empty() ? beta_m : strands.beta[2 * size_t(s)];
    }
    float beta_n_of(uint32_t s) const {
        return strands.beta.empty() ? beta_n : strands.beta[2 * size_t(s) + 1];
    }

    // A moving skin's strands at the shutter's later motion steps (the object's
    // MeshData::later_positions), the same strands as `strands.points`; empty: still.
    std::vector<std::vector<float>> later_points;

    // Centre-line point and unit tangent (root to tip: the hair BSDF's +x, which the
    // cuticle tilt depends on) of segment `prim` at curve parameter u, at shutter time
    // `time`.
    void centre(unsigned prim, float u, float time, Vec3f *c, Vec3f *tangent,
                float *radius) const;

    // Widened strands (min_pixel_width): strands.points with every radius widened
    // (what the camera's geometry intersects); empty when none was.
    std::vector<float> wide_points;
    std::vector<std::vector<float>> later_wide_points;  // ... at later_points' steps
    bool widened() const { return !wide_points.empty(); }
    // The share of a hit at parameter u of segment `prim` that is fibre: own radius over
    // widened radius there (1 where the strand is not widened).
    float opacity(unsigned prim, float u) const;
};

class FurGeometry {
  public:
    // Grows the fur of every object that has some, attaches the curves to `scene` and
    // recommits it. Throws pelage::InputError naming objects[i].fur when the fur cannot
    // be grown (e.g. more strands than max_strands).
    FurGeometry(const SceneDesc &desc, EmbreeScene &scene,
                const ObjectPigmentLookup &pigment);
    ~FurGeometry();
    FurGeometry(const FurGeometry &) = delete;
    FurGeometry &operator=(const FurGeometry &) = delete;

    // The layer a hit belongs to, or null when geom_id is not fur.
    const FurLayer *layer_of(unsigned geom_id) const {
        return geom_id < m_layer_of_geom.size() && m_layer_of_geom[geom_id] >= 0
                   ? &m_layers[size_t(m_layer_of_geom[geom_id])]
                   : nullptr;
    }
    const std::vector<FurLayer> &layers() const { return m_layers; }
    size_t num_strands() const;
    // Whether any strand was widened: camera rays then carry a stratified ξ and trace
    // camera_scene(): the scene's meshes and lights (same geometry IDs), each layer's
    // widened strands under its fibres' ID, the fibres of the others.
    bool widened() const { return m_camera_scene != nullptr; }
    RTCScene camera_scene() const { return m_camera_scene; }
    uint64_t widened_points() const { return m_widened_points; }
    double grow_seconds() const { return m_grow_seconds; }      // strands (renderer/fur)
    double embree_seconds() const { return m_embree_seconds; }  // curves + BVH commit

  private:
    void attach_fibres(EmbreeScene &scene);
    void build_camera_scene(EmbreeScene &scene, unsigned scene_geometries);

    std::vector<FurLayer> m_layers;
    std::vector<int> m_layer_of_geom;
    RTCScene m_camera_scene = nullptr;
    double m_grow_seconds = 0, m_embree_seconds = 0;
    uint64_t m_widened_points = 0;
};

}  // namespace pelage::renderer
