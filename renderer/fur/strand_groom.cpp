#include "renderer/fur/strand_groom.h"

#include <algorithm>
#include <cmath>

namespace pelage::renderer {

namespace {

using Groomed = FurParams::Groomed;

// Sizes and density scale with the object, so their per-type values are factors.
bool is_factor(Groomed k) {
    return k == Groomed::length || k == Groomed::density || k == Groomed::root_radius ||
           k == Groomed::tip_radius;
}

// A value where the coat's is `coat`: the type's (factor or value), then each region's
// lerp in order, as sim::SurfaceControl::value() applies a local value's. A factor
// applies to the regions' values too: "twice as long on the dark patches" holds in a
// region of long hair as well.
float value_at(const FurParams::Varying &v, bool factor, float coat, const float *weights,
               int type) {
    const bool typed = type >= 0 && size_t(type) < v.by_type.size();
    float x = coat;
    if (typed && !factor) x = v.by_type[size_t(type)];
    for (const auto &[region, target] : v.in) x += (target - x) * weights[region];
    if (typed && factor) x *= v.by_type[size_t(type)];
    return x;
}

}  // namespace

float fur_depth(const StrandGroom &g) {
    const float d = g.density * g.length * (g.root_radius + g.tip_radius) *
                    std::cos(g.comb_angle_deg * float(M_PI / 180));
    return std::isfinite(d) ? std::max(d, 0.0f) : 0.0f;
}

StrandGroom coat_groom(const FurParams &p) {
    return {p.length, float(p.density), p.root_radius, p.tip_radius, p.beta_m,
            p.beta_n, p.comb_angle_deg, p.curl_radius, p.curl_turns, p.clump};
}

StrandGroom strand_groom(const FurParams &params, const float *weights, int type) {
    StrandGroom g = coat_groom(params);
    float *out[] = {&g.length,     &g.density, &g.root_radius,    &g.tip_radius,
                    &g.beta_m,     &g.beta_n,  &g.comb_angle_deg, &g.curl_radius,
                    &g.curl_turns, &g.clump};
    for (size_t k = 0; k < size_t(Groomed::count); ++k) {
        const FurParams::Varying &v = params.varying[k];
        if (!v.varies()) continue;  // exactly the coat's value
        *out[k] = value_at(v, is_factor(Groomed(k)), *out[k], weights, type);
    }
    return g;
}

void region_weights(const SkinMesh &mesh, const SurfacePoint &root, float *out) {
    const size_t R = mesh.num_regions;
    const float *c = &mesh.region_corners[3 * R * size_t(root.triangle)];
    const float b1 = root.b1, b2 = root.b2, b0 = 1 - b1 - b2;
    for (size_t i = 0; i < R; ++i)
        out[i] = std::clamp(b0 * c[i] + b1 * c[R + i] + b2 * c[2 * R + i], 0.0f, 1.0f);
}

double max_density(const FurParams &params) {
    const FurParams::Varying &v = params.vary(Groomed::density);
    double d = params.density;
    for (const auto &[region, value] : v.in) d = std::max(d, double(value));
    if (!v.by_type.empty())
        d *= double(*std::max_element(v.by_type.begin(), v.by_type.end()));
    return d;
}

}  // namespace pelage::renderer
