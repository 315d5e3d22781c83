// The fur layer's parameters, as an object's `"fur": {…}` block in a scene file describes
// them (renderer/scene_file/scene_fur.cpp parses and validates them; README "Fur"
// documents each key). Lengths and radii are in world units (after the object's
// transform), density in strands per world unit of area, angles in degrees.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/control/control_spec.h"
#include "sim/core/vec.h"
#include "sim/field/field_spec.h"

namespace pelage::renderer {

struct FurParams {
    // --- Roots ---
    double density = 20000;  // strands per unit area
    uint64_t seed = 1;
    uint64_t max_strands = 20'000'000;  // refuse to build more (memory guard)

    // --- Shape ---
    float length = 0.05f;
    float length_variation = 0.2f;  // each strand's length × U[1 − v, 1 + v]
    float root_radius = 0.0015f, tip_radius = 0.0003f;
    int segments = 8;
    // world: comb_direction; normal: strands stand up; field: one direction per skin
    // triangle from a tangent field (SkinMesh::comb_by_corner), as a preset's
    // anisotropy field is given: comb_field, or the object's pattern's own field when
    // comb_pattern_field.
    enum class Comb { world, normal, field } comb = Comb::world;
    Vec3f comb_direction{0, -1, 0};  // projected onto each root's tangent plane
    sim::FieldSpec comb_field;
    Vec3f comb_towards{0, -1, 0};  // a field's sense: its axis turned towards this
    int comb_smoothing = 0;        // passes of neighbour averaging of a field comb
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
    // Strands narrower than this many pixels, seen from the scene's camera, are widened
    // to it with their opacity scaled to keep their coverage (renderer/geometry/
    // fur_geometry.h); 0 (the default: short dense fur widened many times comes out too
    // dark, docs/guide/fur.md) turns it off.
    float min_pixel_width = 0;

    // --- A groom: values by cell type and by body region (renderer/fur/strand_groom.h)
    // --- Per cell type, sizes and density are factors of the coat's value (which scales
    // with the object, scale_defaults_to()); the others replace it. Per region, the
    // (region, value) pairs of a local value as the presets have them
    // (sim/control/control_spec.h, LocalValue), applied in order after the type's value:
    // each moves it to lerp(current, value, region weight).
    enum class Groomed {
        length,
        density,
        root_radius,
        tip_radius,
        beta_m,
        beta_n,
        comb_angle,
        curl_radius,
        curl_turns,
        clump,
        count
    };
    struct Varying {
        std::vector<float> by_type;             // {} = the same for every type
        std::vector<std::pair<int, float>> in;  // (region index, value)
        bool varies() const { return !by_type.empty() || !in.empty(); }
    };
    std::array<Varying, size_t(Groomed::count)> varying;
    Varying &vary(Groomed k) { return varying[size_t(k)]; }
    const Varying &vary(Groomed k) const { return varying[size_t(k)]; }
    // Hair colour by region: each (region, colour) moves a strand's σ_a towards that
    // colour's, after its type's pigment.
    std::vector<std::pair<int, Rgb>> colour_in;
    // The fur's own "regions", named as in a preset (only regions: no masks or values).
    sim::ControlSpec regions;

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
