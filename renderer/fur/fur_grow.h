// Grows the fur of one object: area-uniform roots (thinned per cell type when density
// depends on it), each strand's absorption from the skin's own lookup at its root (by
// default the colour the skin shows there, FurParams::Pigment), the
// strand's centre line (comb, gravity, curl, clumping) and its radii, written in the
// layout Embree's curves read (FLOAT4: x, y, z, radius per control point).
//
// Determinism: every random number is a hash of (seed, stream, candidate index, dim);
// strands keep candidate order, so the result is identical at any thread count.
// Thread-safety: `lookup` is called concurrently from TBB workers.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "renderer/fur/fur_params.h"
#include "renderer/fur/root_sampling.h"

namespace pelage::renderer {

// What the skin says at a root: the colour it shows (PelageShade::albedo), its pigment,
// its cell type (−1 when unknown), and its matte ids (PelageShade::matte; bit k of
// matte_written set when matte[k] holds one).
struct RootPigment {
    Rgb colour{0.5f, 0.5f, 0.5f};
    float eumelanin = 0, pheomelanin = 0;
    int cell_type = -1;
    uint32_t matte[3] = {0, 0, 0};
    uint32_t matte_written = 0;
};
using PigmentLookup = std::function<RootPigment(const SurfacePoint &, Vec3f p, Vec3f n)>;

struct Strands {
    int segments = 0;                // curve segments per strand
    uint32_t points_per_strand = 0;  // control points per strand
    // FLOAT4 control points, points_per_strand per strand. Round curves are uniform cubic
    // B-splines whose first and last control points are phantoms (2·p0 − p1), so the
    // curve starts exactly at the root and ends at the tip; flat curves are the
    // polyline itself (linear).
    std::vector<float> points;
    std::vector<Rgb>
        sigma_a;  // absorption per fibre radius, per strand (hair_pigments.h)
    // β_m, β_n per strand when the groom varies them (strand_groom.h), else empty: the
    // layer's FurParams values hold for every strand.
    std::vector<float> beta;
    std::vector<SurfacePoint> roots;
    // The root's matte ids and their bits, 4 per strand, so a strand shows in the
    // skin's Cryptomatte layers; empty when no root had any.
    std::vector<uint32_t> matte;
    uint64_t candidates = 0;  // roots drawn before per-type thinning

    size_t size() const { return roots.size(); }
};

// Throws std::invalid_argument for parameters out of range or more than
// params.max_strands candidates.
Strands grow_fur(const FurParams &params, const SkinMesh &mesh,
                 const PigmentLookup &lookup);

// The expected strand count before thinning: the highest density anywhere × area.
double expected_candidates(const FurParams &params, double area);

}  // namespace pelage::renderer
