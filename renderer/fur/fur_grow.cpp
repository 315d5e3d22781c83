#include "renderer/fur/fur_grow.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "renderer/bsdf/hair_pigments.h"
#include "renderer/fur/clump_guides.h"
#include "renderer/fur/fur_hash.h"
#include "renderer/fur/strand_groom.h"
#include "renderer/fur/strand_shape.h"

namespace pelage::renderer {

namespace {

// A strand's σ_a before scale and jitter, and whether it comes from melanins (then the
// two pigments are jittered independently, as natural hair's ratio varies).
struct StrandAbsorption {
    Rgb sigma_a;
    bool melanin;
    float eumelanin, pheomelanin;
};

// `depth`: the coat's at the root (fur_depth), in which a colour is matched over the
// skin the root grows from.
StrandAbsorption absorption(const FurParams &params, const RootPigment &pg, float beta_n,
                            float depth) {
    using Kind = FurParams::Pigment::Kind;
    const FurParams::Pigment &pig =
        pg.cell_type >= 0 && size_t(pg.cell_type) < params.pigment_by_type.size()
            ? params.pigment_by_type[size_t(pg.cell_type)]
            : params.pigment;
    auto finite = [](float x) { return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f; };
    switch (pig.kind) {
        case Kind::skin_melanin:
        case Kind::melanin: {
            const bool skin = pig.kind == Kind::skin_melanin;
            const float eu = finite(skin ? pg.eumelanin : pig.eumelanin);
            const float ph = finite(skin ? pg.pheomelanin : pig.pheomelanin);
            return {sigma_a_from_melanin(eu, ph), true, eu, ph};
        }
        case Kind::colour:
            return {sigma_a_from_coat_colour(pig.colour, beta_n, depth, pg.colour), false,
                    0, 0};
        case Kind::absorption:
            return {pig.sigma_a, false, 0, 0};
        case Kind::skin:
            break;
    }
    // The skin's albedo, kept inside the inversion's domain (0, 1]: a black skin gives
    // the darkest fibre the fit reaches rather than infinite absorption.
    auto in_domain = [&](float x) { return std::clamp(finite(x), 1e-3f, 1.0f); };
    const Rgb c{in_domain(pg.colour.x), in_domain(pg.colour.y), in_domain(pg.colour.z)};
    return {sigma_a_from_coat_colour(c, beta_n, depth, pg.colour), false, 0, 0};
}

void check(bool ok, const std::string &what) {
    if (!ok) throw std::invalid_argument("fur: " + what);
}

}  // namespace

double expected_candidates(const FurParams &params, double area) {
    return max_density(params) * area;
}

Strands grow_fur(const FurParams &params, const SkinMesh &mesh,
                 const PigmentLookup &lookup) {
    check(params.segments >= 1 && params.segments <= max_segments,
          "segments = " + std::to_string(params.segments) + ": must be in [1, 64]");
    check(params.density >= 0 && std::isfinite(params.density), "density must be >= 0");
    check(params.length > 0 && params.root_radius > 0 && params.tip_radius > 0,
          "length and radii must be > 0");
    const RootSampler sampler(mesh);
    const double expected = expected_candidates(params, sampler.area());
    check(expected <= double(params.max_strands),
          "density × area asks for " + std::to_string(uint64_t(expected)) +
              " strands, more than max_strands = " + std::to_string(params.max_strands));
    const uint64_t n = candidate_count(expected, params.seed);
    const double top_density = max_density(params);
    const size_t R = mesh.num_regions;
    check(R == 0 || mesh.region_corners, "regions without their values on the skin");
    for (size_t k = 0; k < size_t(FurParams::Groomed::count); ++k)
        for (const auto &[region, value] : params.varying[k].in)
            check(region >= 0 && size_t(region) < R, "a value names an unknown region");
    for (const auto &[region, value] : params.colour_in)
        check(region >= 0 && size_t(region) < R, "a colour names an unknown region");

    // --- Candidates: root, pigment, and whether per-type thinning keeps them ---
    std::vector<SurfacePoint> cand(n);
    std::vector<RootPigment> pigment(n);
    std::vector<uint8_t> keep(n);
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, n, 4096), [&](auto range) {
        std::vector<float> weights(R);
        for (uint64_t i = range.begin(); i != range.end(); ++i) {
            cand[i] = sampler.sample(params.seed, i);
            Vec3f p, nrm;
            sampler.point_normal(cand[i], &p, &nrm);
            pigment[i] = lookup(cand[i], p, nrm);
            // Thinning keeps a root with probability density(root) / max density: the
            // kept roots are area-uniform wherever the density is the same.
            if (R) region_weights(mesh, cand[i], weights.data());
            const double density =
                strand_groom(params, weights.data(), pigment[i].cell_type).density;
            const double keep_p = top_density > 0 ? density / top_density : 0.0;
            keep[i] = uniform(params.seed, Stream::thinning, i, 0) < keep_p;
        }
    });
    // --- Compact in candidate order (deterministic) ---
    std::vector<uint64_t> index;
    index.reserve(n);
    for (uint64_t i = 0; i < n; ++i)
        if (keep[i]) index.push_back(i);
    std::vector<uint8_t>().swap(keep);

    Strands out;
    const int S = params.segments;
    const bool round = params.curve == FurParams::Curve::round;
    out.segments = S;
    out.points_per_strand = uint32_t(round ? S + 3 : S + 1);
    out.candidates = n;
    const size_t m = index.size();
    out.points.resize(m * out.points_per_strand * 4);
    out.sigma_a.resize(m);
    if (beta_varies(params)) out.beta.resize(2 * m);
    out.roots.resize(m);
    bool any_matte = false;
    for (const uint64_t i : index) any_matte = any_matte || pigment[i].matte_written;
    if (any_matte) out.matte.resize(4 * m);

    const ClumpGuides guides(params, mesh, sampler);
    // --- Grow every kept strand ---
    tbb::parallel_for(tbb::blocked_range<size_t>(0, m, 1024), [&](auto range) {
        Vec3f line[max_segments + 1];
        std::vector<float> weights(R);
        for (size_t j = range.begin(); j != range.end(); ++j) {
            const uint64_t i = index[j];
            const SurfacePoint &root = cand[i];
            const RootPigment &pg = pigment[i];
            if (R) region_weights(mesh, root, weights.data());
            const StrandGroom g = strand_groom(params, weights.data(), pg.cell_type);
            Vec3f p, nrm;
            sampler.point_normal(root, &p, &nrm);
            const float v = params.length_variation;
            const float L =
                g.length *
                float(1 + v * (2 * uniform(params.seed, Stream::shape, i, 0) - 1));
            const StrandRandom rnd{float(uniform(params.seed, Stream::shape, i, 1)),
                                   float(uniform(params.seed, Stream::shape, i, 2)),
                                   float(uniform(params.seed, Stream::shape, i, 3))};
            grow_centre_line(params, g, p, nrm, comb_at(params, mesh, root),
                             std::max(L, 1e-6f * params.length), rnd, line);
            guides.pull(line, g.clump, g.length / params.length);

            // --- Control points with radii (linear from root to tip) ---
            float *P = &out.points[j * out.points_per_strand * 4];
            auto put = [&](Vec3f q, float r) {
                P[0] = q.x;
                P[1] = q.y;
                P[2] = q.z;
                P[3] = r;
                P += 4;
            };
            auto radius = [&](int k) {
                const float s = float(k) / float(S);
                return g.root_radius * (1 - s) + g.tip_radius * s;
            };
            if (round) put(line[0] * 2 - line[1], 2 * radius(0) - radius(1));
            for (int k = 0; k <= S; ++k) put(line[k], radius(k));
            if (round)
                put(line[S] * 2 - line[S - 1],
                    std::max(2 * radius(S) - radius(S - 1), 0.0f));

            // --- Absorption: from the skin at the root, scaled and jittered ---
            const float j_eu = float(2 * uniform(params.seed, Stream::pigment, i, 0) - 1);
            const float j_ph = float(2 * uniform(params.seed, Stream::pigment, i, 1) - 1);
            const float depth = fur_depth(g);
            const StrandAbsorption a = absorption(params, pg, g.beta_n, depth);
            const float k = params.melanin_scale, jit = params.melanin_jitter;
            Rgb sa = a.melanin
                         ? sigma_a_from_melanin(a.eumelanin * k * (1 + jit * j_eu),
                                                a.pheomelanin * k * (1 + jit * j_ph))
                         : a.sigma_a * (k * (1 + jit * j_eu));
            // Hair colour by region: towards each region's colour, by its weight.
            for (const auto &[region, colour] : params.colour_in) {
                const Rgb target =
                    sigma_a_from_coat_colour(colour, g.beta_n, depth, pg.colour) *
                    (k * (1 + jit * j_eu));
                sa = sa + (target - sa) * weights[size_t(region)];
            }
            auto finite = [](float x) {
                return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f;
            };
            out.sigma_a[j] = {finite(sa.x), finite(sa.y), finite(sa.z)};
            out.roots[j] = root;
            if (!out.beta.empty()) {
                out.beta[2 * j] = g.beta_m;
                out.beta[2 * j + 1] = g.beta_n;
            }
            if (any_matte) {
                for (int k = 0; k < 3; ++k) out.matte[4 * j + k] = pg.matte[k];
                out.matte[4 * j + 3] = pg.matte_written;
            }
        }
    });
    return out;
}

}  // namespace pelage::renderer
