// `pelage bench hair`: the Chiang et al. 2016 hair BSDF (renderer/bsdf/hair_bsdf.h).
// Prints one JSON object: furnace_max_error (a contract: the worst |∫ f|cos θ_i| dω − 1|
// over a fixed, seeded set of σ_a = 0 fibres with random β_m, β_n ∈ [0.1, 1], α ∈ [−5°,
// 5°], h and wo, by the midpoint quadrature of renderer/bsdf/hair_furnace.h), the worst
// |∫ pdf dω − 1|, and nanoseconds per eval / pdf / sample call on one thread.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "apps/bench/bench.h"
#include "renderer/bsdf/hair_bsdf.h"
#include "renderer/bsdf/hair_furnace.h"

namespace pelage::renderer::cli {
namespace {

struct BenchHairOptions {
    int configs = 32;
    int theta_steps = 512;
    uint32_t seed = 6;
    BenchOutput out;
};

struct Rng {
    explicit Rng(uint32_t seed) : gen(seed) {}
    float operator()() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(gen); }
    float in(float a, float b) { return a + (b - a) * (*this)(); }
    Vec3f direction() {
        const float z = 1 - 2 * (*this)(), r = std::sqrt(std::max(0.0f, 1 - z * z));
        const float phi = 2 * pi * (*this)();
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    std::mt19937 gen;
};

renderer::HairParams random_params(Rng &rng, bool absorbing) {
    renderer::HairParams p = absorbing ? renderer::HairParams::from_melanin(
                                             rng.in(0, 4), rng.in(0, 2), 0.3f, 0.3f)
                                       : renderer::HairParams{};
    p.beta_m = rng.in(0.1f, 1.0f);
    p.beta_n = rng.in(0.1f, 1.0f);
    p.alpha = rng.in(-5.0f, 5.0f) * pi / 180;
    return p;
}

int run(const BenchHairOptions &o) {
    // --- White furnace and pdf normalisation over the fixed set ---
    Rng rng(o.seed);
    double furnace_max = 0, pdf_max = 0;
    const Timer furnace_timer;
    for (int k = 0; k < o.configs; ++k) {
        const renderer::HairBsdf white(random_params(rng, false), rng.in(-1, 1));
        const Vec3f wo = rng.direction();
        const renderer::FurnaceResult r = renderer::furnace_quadrature(
            white, wo, o.theta_steps, 2 * o.theta_steps, true);
        for (int c = 0; c < 3; ++c)
            furnace_max =
                std::max(furnace_max, std::abs(double(r.f_cos_integral[c]) - 1));
        pdf_max = std::max(pdf_max, std::abs(r.pdf_integral - 1));
    }
    const double furnace_seconds = furnace_timer.seconds();

    // --- Timing: 256 absorbing fibres, 2^20 calls each of eval, pdf, sample ---
    std::vector<renderer::HairBsdf> fibres;
    for (int k = 0; k < 256; ++k)
        fibres.emplace_back(random_params(rng, true), rng.in(-1, 1));
    const int n = 1 << 20;
    std::vector<Vec3f> wo(n), wi(n);
    std::vector<float> u(3 * n);
    for (int k = 0; k < n; ++k) {
        wo[k] = rng.direction();
        wi[k] = rng.direction();
    }
    for (float &x : u) x = rng();
    double sink = 0;
    auto time_ns = [&](auto &&call) {
        const Timer t;
        for (int k = 0; k < n; ++k) sink += call(fibres[k & 255], k);
        return 1e9 * t.seconds() / n;
    };
    const double eval_ns = time_ns(
        [&](const renderer::HairBsdf &b, int k) { return b.eval(wo[k], wi[k]).y; });
    const double pdf_ns =
        time_ns([&](const renderer::HairBsdf &b, int k) { return b.pdf(wo[k], wi[k]); });
    const double sample_ns = time_ns([&](const renderer::HairBsdf &b, int k) {
        const auto s = b.sample(wo[k], u[3 * k], u[3 * k + 1], u[3 * k + 2]);
        return s ? s->weight.y : 0.0f;
    });
    const Timer build_timer;
    for (int k = 0; k < n; ++k) {
        const renderer::HairBsdf b(fibres[k & 255].params(), 2 * u[k] - 1);
        sink += b.h();
    }
    const double construct_ns = 1e9 * build_timer.seconds() / n;

    const nlohmann::json j = {{"benchmark", "hair"},
                              {"furnace_max_error", furnace_max},
                              {"pdf_integral_max_error", pdf_max},
                              {"furnace_configs", o.configs},
                              {"furnace_grid", {o.theta_steps, 2 * o.theta_steps}},
                              {"furnace_seconds", furnace_seconds},
                              {"seed", o.seed},
                              {"eval_ns", eval_ns},
                              {"pdf_ns", pdf_ns},
                              {"sample_ns", sample_ns},
                              {"construct_ns", construct_ns},
                              {"checksum", sink}};
    o.out.emit(j);
    return 0;
}

}  // namespace

Runner add_bench_hair(CLI::App &bench) {
    auto o = std::make_shared<BenchHairOptions>();
    CLI::App *sub = bench.add_subcommand(
        "hair", "Hair BSDF: white furnace error, pdf normalisation, ns per call");
    sub->add_option("--configs", o->configs,
                    "Random σ_a = 0 fibres in the furnace set (default 32)")
        ->check(CLI::Range(1, 10000));
    sub->add_option("--theta-steps", o->theta_steps,
                    "Quadrature steps in θ_i; φ_i gets twice as many (default 512)")
        ->check(CLI::Range(16, 8192));
    sub->add_option("--sampler-seed", o->seed,
                    "Seed of the sampled furnace set and timing inputs (default 6)");
    refuse_pattern_seed(*sub, "--sampler-seed");
    o->out.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
