#include "renderer/geometry/fur_geometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "renderer/bsdf/hair_bsdf.h"
#include "renderer/core/motion_step.h"
#include "renderer/core/setup_phase.h"
#include "renderer/geometry/embree_scene.h"
#include "renderer/geometry/fur_skin.h"
#include "sim/core/hash.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Whether hit i of the packet leaves a round curve's tube: Embree's Ng there is the
// tube's outward normal (RTC_GEOMETRY_TYPE_CURVE(3)), so the ray started inside it.
bool leaves_tube(const RTCFilterFunctionNArguments *args, unsigned i) {
    const unsigned N = args->N;
    return RTCRayN_dir_x(args->ray, N, i) * RTCHitN_Ng_x(args->hit, N, i) +
               RTCRayN_dir_y(args->ray, N, i) * RTCHitN_Ng_y(args->hit, N, i) +
               RTCRayN_dir_z(args->ray, N, i) * RTCHitN_Ng_z(args->hit, N, i) >
           0;
}

// The uniform cubic B-spline basis at u (Embree's round curves, FurLayer::centre()).
void bspline_basis(float u, float b[4]) {
    const float v = 1 - u;
    b[0] = v * v * v / 6;
    b[1] = (3 * u * u * u - 6 * u * u + 4) / 6;
    b[2] = (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6;
    b[3] = u * u * u / 6;
}

// From this many strands in a scene its BVH takes Embree's compact layout.
constexpr size_t compact_strands = 1000000;

// A number in [0, 1) from 64 bits.
float unit_hash(uint64_t x) { return float(mix64(x) >> 40) * 0x1p-24f; }

// Whether ray i passes a widened strand beyond its tip or before its root: the end caps
// of a widened tube reach one widened radius past the fibre's ends, where the fibre
// covers nothing. Tested at the ray's closest approach to the end's tangent line (the
// hit point itself for a ray along it): in the image, the widened strand then ends
// where the fibre does. Without it every tip adds a cap about a pixel wide to the
// strand's coverage.
bool beyond_ends(const FurLayer &layer, const RTCFilterFunctionNArguments *args,
                 unsigned i, unsigned prim) {
    const unsigned S = unsigned(layer.strands.segments);
    const unsigned k = prim % S;
    if (k != 0 && k + 1 != S) return false;
    const unsigned N = args->N;
    const Vec3f o{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i),
                  RTCRayN_org_z(args->ray, N, i)};
    const Vec3f d{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i),
                  RTCRayN_dir_z(args->ray, N, i)};
    const float t_hit = RTCRayN_tfar(args->ray, N, i);
    // The signed distance along the end's tangent of the ray's point closest to it.
    auto past = [&](float u) {
        Vec3f c, x;
        float radius;
        layer.centre(prim, u, RTCRayN_time(args->ray, N, i), &c, &x, &radius);
        const Vec3f w = o - c;
        const float a = dot(d, d), b = dot(d, x);
        const float den = a - b * b;
        const float t = den > 1e-6f * a ? (b * dot(x, w) - dot(d, w)) / den : t_hit;
        return dot(w + d * t, x);
    };
    return (k + 1 == S && past(1) > 0) || (k == 0 && past(0) < 0);
}

// The fibres' filter: rejects hits on the strand the ray left (fur_ray_id()) and, on
// round curves, hits on the inside of any tube.
void skip_own_strand(const RTCFilterFunctionNArguments *args) {
    const FurLayer &layer = *static_cast<const FurLayer *>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned id = RTCRayN_id(args->ray, args->N, i);
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const unsigned strand =
            layer.strand_offset + prim / unsigned(layer.strands.segments);
        if ((id & fur_skip_mask) == strand + 1 || (layer.round && leaves_tube(args, i)))
            args->valid[i] = 0;
    }
}

// The widened strands' filter (camera rays, the only ones they meet): a hit is kept with
// probability its opacity, by the ray's stratified ξ rotated by a hash of the strand, and
// never past the fibre's ends.
void keep_by_opacity(const RTCFilterFunctionNArguments *args) {
    const FurLayer &layer = *static_cast<const FurLayer *>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned id = RTCRayN_id(args->ray, args->N, i);
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const float alpha = layer.opacity(prim, RTCHitN_u(args->hit, args->N, i));
        if (beyond_ends(layer, args, i, prim)) {
            args->valid[i] = 0;
            continue;
        }
        if (alpha >= 1) continue;
        const unsigned strand =
            layer.strand_offset + prim / unsigned(layer.strands.segments);
        const float xi = (float((id >> fur_skip_bits) & 31u) + 0.5f) / 32;
        float r = xi + unit_hash(0x9e3779b97f4a7c15ull * (uint64_t(strand) + 1));
        r -= std::floor(r);
        if (r >= alpha) args->valid[i] = 0;
    }
}

// The widened control points: every radius under `k` × its distance from the camera (k:
// half the minimum width's angle) raised to that, into layer.wide_points; the number
// raised (none: wide_points stays empty).
uint64_t widen(FurLayer &layer, Vec3f camera, float k) {
    const std::vector<float> &P = layer.strands.points;
    const size_t n = P.size() / 4;
    uint64_t count = 0;
    for (size_t j = 0; j < n; ++j) {
        const Vec3f e = Vec3f{P[4 * j], P[4 * j + 1], P[4 * j + 2]} - camera;
        count += P[4 * j + 3] < k * length(e);
    }
    if (count == 0) return 0;
    layer.wide_points = P;
    for (size_t j = 0; j < n; ++j) {
        const Vec3f e = Vec3f{P[4 * j], P[4 * j + 1], P[4 * j + 2]} - camera;
        layer.wide_points[4 * j + 3] = std::max(P[4 * j + 3], k * length(e));
    }
    // A moving layer keeps the widths the shutter's opening gave it.
    for (const std::vector<float> &later : layer.later_points) {
        std::vector<float> &W = layer.later_wide_points.emplace_back(later);
        for (size_t j = 0; j < n; ++j) W[4 * j + 3] = layer.wide_points[4 * j + 3];
    }
    return count;
}

// Attaches one curve geometry of `type` over `points` (the layer's fibres, or its widened
// strands) and their later motion steps `later`, with `filter`, to `target`: under `id`,
// or the next free ID when it is RTC_INVALID_GEOMETRY_ID. Returns the ID.
unsigned attach(EmbreeScene &scene, FurLayer &layer, RTCGeometryType type,
                const std::vector<float> &points,
                const std::vector<std::vector<float>> &later, RTCFilterFunctionN filter,
                RTCScene target, unsigned id) {
    const Strands &s = layer.strands;
    RTCGeometry g = rtcNewGeometry(scene.device(), type);
    const size_t num_points = s.size() * s.points_per_strand;
    // A moving layer: one buffer per motion step (embree_scene.h).
    rtcSetGeometryTimeStepCount(g, unsigned(1 + later.size()));
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                               points.data(), 0, 4 * sizeof(float), num_points);
    for (size_t k = 0; k < later.size(); ++k)
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, unsigned(k + 1),
                                   RTC_FORMAT_FLOAT4, later[k].data(), 0,
                                   4 * sizeof(float), num_points);
    const size_t num_segments = s.size() * size_t(s.segments);
    auto *index = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), num_segments));
    if (!index) {
        rtcReleaseGeometry(g);
        scene.check();
        throw std::runtime_error("Embree could not allocate the fur's index buffer");
    }
    for (size_t strand = 0; strand < s.size(); ++strand)
        for (int k = 0; k < s.segments; ++k)
            index[strand * size_t(s.segments) + size_t(k)] =
                uint32_t(strand * s.points_per_strand + size_t(k));
    rtcSetGeometryUserData(g, &layer);
    rtcSetGeometryIntersectFilterFunction(g, filter);
    rtcSetGeometryOccludedFilterFunction(g, filter);
    rtcCommitGeometry(g);
    if (id == RTC_INVALID_GEOMETRY_ID)
        id = rtcAttachGeometry(target, g);
    else
        rtcAttachGeometryByID(target, g, id);
    rtcReleaseGeometry(g);
    return id;
}

}  // namespace

void FurLayer::centre(unsigned prim, float u, float time, Vec3f *c, Vec3f *tangent,
                      float *radius) const {
    const unsigned S = unsigned(strands.segments);
    const size_t first = size_t(prim / S) * strands.points_per_strand + prim % S;
    const float *P = &strands.points[4 * first];
    // A moving strand: its control points at `time`, as Embree interpolates them.
    float moved[16];
    if (!later_points.empty()) {
        const auto [i, f] = motion_step(time, later_points.size());
        const float *A = i == 0 ? P : &later_points[i - 1][4 * first];
        const float *B = &later_points[i][4 * first];
        for (int k = 0; k < (round ? 16 : 8); ++k) moved[k] = A[k] * (1 - f) + B[k] * f;
        P = moved;
    }
    auto pt = [&](int k) { return Vec3f{P[4 * k], P[4 * k + 1], P[4 * k + 2]}; };
    if (!round) {
        *c = pt(0) * (1 - u) + pt(1) * u;
        *tangent = pt(1) - pt(0);
        *radius = P[3] * (1 - u) + P[7] * u;
    } else {
        float b[4];
        bspline_basis(u, b);
        const float v = 1 - u;
        const float db[4] = {-v * v / 2, (3 * u * u - 4 * u) / 2,
                             (-3 * u * u + 2 * u + 1) / 2, u * u / 2};
        *c = pt(0) * b[0] + pt(1) * b[1] + pt(2) * b[2] + pt(3) * b[3];
        *tangent = pt(0) * db[0] + pt(1) * db[1] + pt(2) * db[2] + pt(3) * db[3];
        *radius = P[3] * b[0] + P[7] * b[1] + P[11] * b[2] + P[15] * b[3];
    }
    const float len = length(*tangent);
    *tangent = len > 0 ? *tangent / len : Vec3f{1, 0, 0};
}

float FurLayer::opacity(unsigned prim, float u) const {
    if (wide_points.empty()) return 1;
    const unsigned S = unsigned(strands.segments);
    const size_t first = size_t(prim / S) * strands.points_per_strand + prim % S;
    const float *P = &strands.points[4 * first];
    const float *W = &wide_points[4 * first];
    float own, wide;
    if (!round) {
        own = P[3] * (1 - u) + P[7] * u;
        wide = W[3] * (1 - u) + W[7] * u;
    } else {
        float b[4];
        bspline_basis(u, b);
        own = P[3] * b[0] + P[7] * b[1] + P[11] * b[2] + P[15] * b[3];
        wide = W[3] * b[0] + W[7] * b[1] + W[11] * b[2] + W[15] * b[3];
    }
    return wide > 0 ? std::min(1.0f, std::max(own, 0.0f) / wide) : 1.0f;
}

size_t FurGeometry::num_strands() const {
    size_t n = 0;
    for (const FurLayer &l : m_layers) n += l.strands.size();
    return n;
}

namespace {

// One object's fur: its strands grown on `skin` (and on the skin at each later step of
// the shutter, for a moving skin), each taking its pigment from the object's material.
FurLayer grow_layer(const SceneDesc &desc, size_t i, const ObjectGeometry &og,
                    const FurSkin &skin, const ObjectPigmentLookup &pigment) {
    const FurParams &params = skin.params();
    const std::string field = "objects[" + std::to_string(i) + "].fur";
    const PigmentLookup lookup = [&](const SurfacePoint &s, Vec3f p, Vec3f n) {
        return pigment(i, s, p, n);
    };
    FurLayer layer;
    layer.object = uint32_t(i);
    layer.round = params.curve == FurParams::Curve::round;
    layer.beta_m = params.beta_m;
    layer.beta_n = params.beta_n;
    layer.alpha = params.alpha_deg * pi / 180;
    try {
        // The strands' HairBsdf only DCHECKs its parameters at each hit, so they are
        // validated here, once per layer (as scatter_at_strand() builds them; each
        // strand's σ_a is one grow_fur() keeps finite and >= 0).
        HairParams hp;
        hp.beta_m = layer.beta_m;
        hp.beta_n = layer.beta_n;
        hp.alpha = layer.alpha;
        HairBsdf::validate(hp, 0);
        layer.strands = grow_fur(params, skin.mesh(), lookup);
    } catch (const std::invalid_argument &e) {
        throw InputError(desc.path, 0, field, e.what());
    }
    // A moving skin: the same strands grown on each later step of the shutter (the
    // same roots and random numbers, so strand k is the same hair at every step).
    for (unsigned step = 1; step < og.mesh->motion_steps(); ++step) {
        const FurSkin moved(skin, og, step);
        Strands later = grow_fur(params, moved.mesh(), lookup);
        if (later.points.size() != layer.strands.points.size())
            throw std::runtime_error(
                field + ": the fur grew " + std::to_string(later.size()) +
                " strands at motion step " + std::to_string(step) + " and " +
                std::to_string(layer.strands.size()) + " at the shutter's opening");
        layer.later_points.push_back(std::move(later.points));
    }
    return layer;
}

}  // namespace

FurGeometry::FurGeometry(const SceneDesc &desc, EmbreeScene &scene,
                         const ObjectPigmentLookup &pigment) {
    size_t count = 0;
    for (const ObjectDesc &o : desc.objects) count += o.fur.has_value();
    m_layers.reserve(count);  // layers never move: Embree holds pointers into them
    uint64_t offset = 0;
    const unsigned scene_geometries = scene.num_geometries();
    std::optional<SetupPhase> phase(std::in_place, "growing fur");
    for (size_t i = 0; i < desc.objects.size(); ++i) {
        if (!desc.objects[i].fur) continue;
        const ObjectGeometry &og = scene.objects()[i];
        const FurSkin skin(desc, i, og);
        const auto t0 = Clock::now();
        FurLayer layer = grow_layer(desc, i, og, skin, pigment);
        m_grow_seconds += seconds_since(t0);
        if (offset + layer.strands.size() >= fur_skip_mask)
            throw InputError(desc.path, 0, "objects[" + std::to_string(i) + "].fur",
                             "more than " + std::to_string(fur_skip_mask - 1) +
                                 " strands in the scene");
        layer.strand_offset = uint32_t(offset);
        offset += layer.strands.size();
        if (layer.strands.size() == 0) continue;
        // Sub-pixel strands widened for the scene's camera: a pixel spans
        // 2 tan(fov / 2) / height radians.
        if (const float w = skin.params().min_pixel_width; w > 0) {
            const CameraDesc &cam = desc.camera;
            const float pixel = 2 * std::tan(cam.fov_deg * float(pi) / 360) /
                                float(std::max(desc.film.height, 1));
            m_widened_points += widen(layer, cam.position, 0.5f * w * pixel);
        }
        m_layers.push_back(std::move(layer));
    }
    phase.reset();
    phase.emplace("building the BVH with the fur");
    const auto t1 = Clock::now();
    attach_fibres(scene);
    if (m_widened_points > 0) build_camera_scene(scene, scene_geometries);
    m_embree_seconds = seconds_since(t1);
}

// The curves into the top-level scene, which is then rebuilt.
void FurGeometry::attach_fibres(EmbreeScene &scene) {
    for (size_t li = 0; li < m_layers.size(); ++li) {
        FurLayer &layer = m_layers[li];
        const Strands &s = layer.strands;
        layer.geom_id = attach(scene, layer,
                               layer.round ? RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE
                                           : RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE,
                               s.points, layer.later_points, skip_own_strand,
                               scene.scene(), RTC_INVALID_GEOMETRY_ID);
        if (m_layer_of_geom.size() <= layer.geom_id)
            m_layer_of_geom.resize(layer.geom_id + 1, -1);
        m_layer_of_geom[layer.geom_id] = int(li);
    }
    if (m_layers.empty()) return;
    // Embree's high-quality (spatial split) build costs seconds per 100 k strands for
    // curves; the medium build is several times faster and traces about as fast.
    rtcSetSceneBuildQuality(scene.scene(), RTC_BUILD_QUALITY_MEDIUM);
    // A groom of millions of strands is bound by memory: Embree's compact layout
    // (curve primitives by index, not copied) about halves the peak for slightly fewer
    // rays per second (docs/performance.md, "Fur"), so it is taken from compact_strands
    // strands on.
    if (num_strands() >= compact_strands)
        rtcSetSceneFlags(scene.scene(),
                         rtcGetSceneFlags(scene.scene()) | RTC_SCENE_FLAG_COMPACT);
    rtcCommitScene(scene.scene());
    scene.check();
}

// The camera scene: the same geometries under the same IDs, each widened layer's fibres
// replaced by its widened strands (ribbons facing the ray).
void FurGeometry::build_camera_scene(EmbreeScene &scene, unsigned scene_geometries) {
    RTCScene camera = rtcNewScene(scene.device());
    try {
        rtcSetSceneBuildQuality(camera, RTC_BUILD_QUALITY_MEDIUM);
        for (unsigned id = 0; id < scene_geometries; ++id)
            rtcAttachGeometryByID(camera, rtcGetGeometry(scene.scene(), id), id);
        for (FurLayer &layer : m_layers) {
            if (!layer.widened())
                rtcAttachGeometryByID(
                    camera, rtcGetGeometry(scene.scene(), layer.geom_id), layer.geom_id);
            else
                attach(scene, layer,
                       layer.round ? RTC_GEOMETRY_TYPE_FLAT_BSPLINE_CURVE
                                   : RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE,
                       layer.wide_points, layer.later_wide_points, keep_by_opacity,
                       camera, layer.geom_id);
        }
        rtcCommitScene(camera);
        scene.check();
    } catch (...) {
        rtcReleaseScene(camera);
        throw;
    }
    m_camera_scene = camera;
}

FurGeometry::~FurGeometry() {
    if (m_camera_scene) rtcReleaseScene(m_camera_scene);
}

}  // namespace pelage::renderer
