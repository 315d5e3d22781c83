// The fur layer's parameters, as an object's `"fur": {…}` block in a scene file describes
// them (renderer/scene_file/scene_fur.cpp parses and validates them; README "Fur"
// documents each key). Lengths and radii are in world units (after the object's
// transform), density in strands per world unit of area, angles in degrees.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/core/vec.h"
#include "sim/field/field_spec.h"

namespace pelage::renderer {

struct FurParams {
    // --- Roots ---
    double density = 20000;  // strands per unit area
    std::vector<float>
        density_by_type;  // multiplier per cell type (darker → denser), {} = 1
    uint64_t seed = 1;
    uint64_t max_strands = 20'000'000;  // refuse to build more (memory guard)

    // --- Shape ---
    float length = 0.05f;
    std::vector<float> length_by_type;  // multiplier per cell type, {} = 1
    float length_variation = 0.2f;      // each strand's length × U[1 − v, 1 + v]
    float root_radius = 0.0015f, tip_radius = 0.0003f;
    int segments = 8;
    // world: comb_direction; normal: strands stand up; field: one direction per skin
    // triangle from a tangent field (SkinMesh::comb_by_triangle), as a preset's
    // anisotropy field is given: comb_field, or the object's pattern's own field when
    // comb_pattern_field.
    enum class Comb { world, normal, field } comb = Comb::world;
    Vec3f comb_direction{0, -1, 0};  // projected onto each root's tangent plane
    sim::FieldSpec comb_field;
    bool comb_pattern_field = false;
    float comb_angle_deg = 30;   // between the root direction and the surface
    float comb_jitter_deg = 8;   // random tilt of each root direction
    float gravity = 0;           // downward bend over the strand (0 none, ~1 strong)
    float curl_radius = 0;       // helix radius as a fraction of the length
    float curl_turns = 0;        // helix turns over the strand
    float clump = 0;             // tip pull towards the clump guide, [0, 1]
    float clump_radius = 0.01f;  // guide spacing: one guide per π·r² of skin

    // --- Pigment and look ---
    // Where a strand's absorption σ_a comes from (renderer/bsdf/hair_pigments.h).
    struct Pigment {
        enum class Kind {
            skin,          // the colour the skin shows under the root, inverted
            skin_melanin,  // the skin's eumelanin and pheomelanin at the root
            colour,        // `colour`, inverted (hair_pigments.h)
            melanin,       // `eumelanin`, `pheomelanin`
            absorption     // `sigma_a` as given
        } kind = Kind::skin;
        Rgb colour{1, 1, 1};   // each channel in (0, 1]
        Rgb sigma_a{0, 0, 0};  // per fibre radius, each channel >= 0
        float eumelanin = 0, pheomelanin = 0;
    };
    Pigment pigment;                       // the whole coat
    std::vector<Pigment> pigment_by_type;  // per cell type, {} = `pigment` everywhere
    float melanin_scale = 1;               // multiplies every strand's σ_a
    float melanin_jitter = 0.1f;  // σ_a × U[1 − j, 1 + j] (melanins: each independently)
    float beta_m = 0.25f, beta_n = 0.3f, alpha_deg = 2;  // hair BSDF (renderer/bsdf)
    enum class Curve { round, flat } curve = Curve::round;

    // The defaults above are for an object of bounding radius 1. Lengths and radii not
    // given scale with the object's radius r and a density not given with 1 / r², so
    // an object in millimetres or in hundreds of units gets the same coat, and the same
    // strand count, as one of unit size.
    enum Given : uint32_t {
        given_density = 1,
        given_length = 2,
        given_root_radius = 4,
        given_tip_radius = 8,
        given_clump_radius = 16
    };
    uint32_t given = 0;  // Given bits: the values the scene file sets
    void scale_defaults_to(double radius) {
        const float k = float(radius);
        if (!(given & given_density)) density /= double(radius) * double(radius);
        if (!(given & given_length)) length *= k;
        if (!(given & given_root_radius)) root_radius *= k;
        if (!(given & given_tip_radius)) tip_radius *= k;
        if (!(given & given_clump_radius)) clump_radius *= k;
        given = ~0u;  // scaled once
    }
};

}  // namespace pelage::renderer
