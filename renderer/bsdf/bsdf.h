// The BSDF interface. BSDFs are value types built per hit in the shading
// frame: directions are local, +z is the shading normal, wo points away from the surface
// towards where light goes. Conventions stated once here:
//   * eval(wo, wi) returns f(wo, wi) WITHOUT the |cos θ_i| factor;
//   * pdf(wo, wi) is the solid-angle density of sample();
//   * sample() returns nullopt for "no sample" (never a zero pdf), and its weight is
//     f · |cos θ_i| / pdf.
// The skin BSDFs (Lambert, coated) are reflective only: wo and wi on the +z side, else
// f = 0. The hair BSDF (hair_bsdf.h) is two-sided and transmissive, in its fibre frame.
#pragma once

#include <concepts>
#include <optional>

#include "renderer/core/math.h"

namespace pelage::renderer {

struct BsdfSample {
    Vec3f wi;
    Rgb f;  // excludes |cos θ_i|
    float pdf;
    Rgb weight;  // f · |cos θ_i| / pdf
    bool specular;
};

template <typename T>
concept Bsdf = requires(const T &b, Vec3f w, float u, float u2) {
    { b.eval(w, w) } -> std::same_as<Rgb>;
    { b.pdf(w, w) } -> std::same_as<float>;
    { b.sample(w, u, u2, u2) } -> std::same_as<std::optional<BsdfSample>>;
    { b.albedo() } -> std::same_as<Rgb>;
};

}  // namespace pelage::renderer
