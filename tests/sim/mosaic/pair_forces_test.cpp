// The pair-force kernel against Walter 1998 Fig. 1's formula summed in doubles, and its
// AVX2 path against its scalar path bit for bit (the cells must not depend on the CPU).
#include "sim/mosaic/pair_forces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "sim/mosaic/cell_types.h"

namespace pelage::sim {
namespace {

// Random candidates in chunks about a few centres (as a triangle's cells cluster), with
// exact bounding circles, and targets among and around them; some targets sit exactly on
// a candidate, and the targets are also candidates (the pushed triangle's own cells).
struct Case {
    std::vector<float> x, z, cx, cz, radius;
    std::vector<int32_t> type;
    std::vector<float> tx, tz, tr, oma;
    uint32_t self = 0;

    ForceCandidates candidates() const {
        return {x.data(),
                z.data(),
                type.data(),
                cx.data(),
                cz.data(),
                radius.data(),
                static_cast<uint32_t>(cx.size())};
    }
    ForceTargets targets() const {
        return {
            tx.data(), tz.data(), tr.data(), oma.data(), static_cast<uint32_t>(tx.size()),
            self};
    }
};

Case make_case(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1), r01(0, 1);
    Case c;
    const int chunks = 3 + int(rng() % 20);
    for (int k = 0; k < chunks; ++k) {
        const float ox = u(rng), oz = u(rng), spread = 0.05f + 0.3f * r01(rng);
        const uint32_t n = 1 + rng() % force_lanes;  // the rest of the chunk is padding
        float lo_x = 1e30f, hi_x = -1e30f, lo_z = 1e30f, hi_z = -1e30f;
        for (uint32_t l = 0; l < force_lanes; ++l) {
            const bool real = l < n;
            const float px = real ? ox + spread * u(rng) : force_padding_position;
            const float pz = real ? oz + spread * u(rng) : force_padding_position;
            c.x.push_back(px);
            c.z.push_back(pz);
            c.type.push_back(real ? int32_t(rng() % max_cell_types) : 0);
            if (real) {
                lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px);
                lo_z = std::min(lo_z, pz), hi_z = std::max(hi_z, pz);
            }
        }
        const float mx = 0.5f * (lo_x + hi_x), mz = 0.5f * (lo_z + hi_z);
        double rad = 0;
        for (uint32_t l = 0; l < n; ++l)
            rad = std::max(rad, std::hypot(double(c.x[k * 8 + l]) - mx,
                                           double(c.z[k * 8 + l]) - mz));
        c.cx.push_back(mx);
        c.cz.push_back(mz);
        c.radius.push_back(float(rad) * 1.0001f);
    }
    while (c.cx.size() % force_lanes) {  // padding chunks, as the relaxation lays them
        c.cx.push_back(force_padding_position);
        c.cz.push_back(force_padding_position);
        c.radius.push_back(0);
        for (uint32_t l = 0; l < force_lanes; ++l) {
            c.x.push_back(force_padding_position);
            c.z.push_back(force_padding_position);
            c.type.push_back(0);
        }
    }
    // The targets are the real cells of chunk `self_chunk`, then some free ones.
    const uint32_t self_chunk = rng() % chunks;
    c.self = self_chunk * force_lanes;
    for (uint32_t l = 0; l < force_lanes && c.x[c.self + l] != force_padding_position;
         ++l)
        c.tx.push_back(c.x[c.self + l]), c.tz.push_back(c.z[c.self + l]);
    for (int k = 0; k < 24; ++k) {
        if (k % 6 == 5) {  // exactly on a real candidate outside the own chunk
            uint32_t p;
            do p = rng() % c.x.size();
            while (c.x[p] == force_padding_position || p / force_lanes == self_chunk);
            c.tx.push_back(c.x[p]), c.tz.push_back(c.z[p]);
        } else {
            c.tx.push_back(u(rng)), c.tz.push_back(u(rng));
        }
    }
    for (size_t k = 0; k < c.tx.size(); ++k) {
        c.tr.push_back(0.1f + 0.4f * r01(rng));
        for (int q = 0; q < max_cell_types; ++q) c.oma.push_back(r01(rng));
    }
    return c;
}

struct Sums {
    std::vector<float> x, z;
    std::vector<uint8_t> coincident;
    std::vector<uint32_t> pairs;
};

template <typename Kernel>
Sums run(const Case &c, Kernel kernel) {
    Sums s{std::vector<float>(c.tx.size(), -7), std::vector<float>(c.tx.size(), -7),
           std::vector<uint8_t>(c.tx.size(), 9), std::vector<uint32_t>(c.tx.size(), 99)};
    kernel(c.targets(), c.candidates(),
           ForceSums{s.x.data(), s.z.data(), s.coincident.data(), s.pairs.data()});
    return s;
}

TEST(PairForces, TheSumsAreWaltersFormulaOverEveryCellWithinR) {
    size_t pairs = 0, touching = 0;
    for (uint32_t seed = 1; seed <= 40; ++seed) {
        const Case c = make_case(seed);
        const Sums s = run(c, add_pair_forces_scalar);
        for (size_t k = 0; k < c.tx.size(); ++k) {
            // Walter 1998 Fig. 1: D = Σ unit(C − P)·(1 − d/r)·(1 − α)·r over 0 < d < r,
            // in doubles, every candidate tried (no chunk is skipped here).
            const double r = c.tr[k];
            double ex = 0, ez = 0, scale = 0;
            bool on_top = false;
            uint32_t within = 0;
            for (size_t p = 0; p < c.x.size(); ++p) {
                if (c.x[p] == force_padding_position || p == c.self + k) continue;
                const double dx = double(c.tx[k]) - c.x[p], dz = double(c.tz[k]) - c.z[p];
                const double d = std::hypot(dx, dz);
                if (d >= r) continue;
                ++within;
                if (d == 0) {
                    on_top = true;
                    continue;
                }
                const double f = (1 - d / r) * c.oma[k * 8 + c.type[p]] * r;
                ex += dx / d * f;
                ez += dz / d * f;
                scale += f;
                ++pairs;
            }
            EXPECT_NEAR(s.x[k], ex, 1e-5 * scale + 1e-7) << "seed " << seed << " k " << k;
            EXPECT_NEAR(s.z[k], ez, 1e-5 * scale + 1e-7) << "seed " << seed << " k " << k;
            EXPECT_EQ(bool(s.coincident[k]), on_top) << "seed " << seed << " k " << k;
            EXPECT_EQ(s.pairs[k], within) << "seed " << seed << " k " << k;
            touching += on_top;
        }
    }
    EXPECT_GT(pairs, 2000u);  // the cases are not empty
    EXPECT_GT(touching, 100u);
}

TEST(PairForces, TheAvx2PathGivesTheScalarPathsBits) {
    if (!pair_forces_use_avx2()) GTEST_SKIP() << "this CPU has no AVX2";
    for (uint32_t seed = 1; seed <= 40; ++seed) {
        const Case c = make_case(seed);
        const Sums a = run(c, add_pair_forces), b = run(c, add_pair_forces_scalar);
        ASSERT_EQ(0, std::memcmp(a.x.data(), b.x.data(), a.x.size() * sizeof(float)))
            << "seed " << seed;
        ASSERT_EQ(0, std::memcmp(a.z.data(), b.z.data(), a.z.size() * sizeof(float)))
            << "seed " << seed;
        ASSERT_EQ(a.coincident, b.coincident) << "seed " << seed;
        ASSERT_EQ(a.pairs, b.pairs) << "seed " << seed;
    }
}

}  // namespace
}  // namespace pelage::sim
