// The pair-force kernel against Walter 1998 Fig. 1's formula summed in doubles, and its
// AVX2 path against its scalar path bit for bit (the cells must not depend on the CPU).
#include "sim/mosaic/pair_forces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "sim/core/vec.h"
#include "sim/mosaic/cell_types.h"

namespace pelage::sim {
namespace {

// Random candidates in chunks about a few centres (as a triangle's cells cluster), each
// chunk in its own frame with a map into the targets' frame and an exact bounding circle
// there, and targets among and around them; some targets sit exactly on a candidate,
// and the targets are also candidates (the pushed triangle's own cells).
struct Case {
    std::vector<float> x, z;  // cells in their own chunk's frame
    std::vector<int32_t> type;
    std::vector<uint32_t> first;                    // per chunk, where its cells are
    std::vector<float> map_c, map_s, map_x, map_z;  // its frame → the targets'
    std::vector<float> cx, cz, radius;              // its circle in the targets' frame
    std::vector<float> tx, tz, tr, oma;
    uint32_t self = 0;

    ForceCandidates candidates() const {
        return {x.data(),     z.data(),      type.data(),
                first.data(), map_c.data(),  map_s.data(),
                map_x.data(), map_z.data(),  cx.data(),
                cz.data(),    radius.data(), static_cast<uint32_t>(cx.size())};
    }
    ForceTargets targets() const {
        return {
            tx.data(), tz.data(), tr.data(), oma.data(), static_cast<uint32_t>(tx.size()),
            self};
    }
};

// The kernel's float map of a cell of chunk c into the targets' frame (what "exactly on
// a candidate" means to it).
float mapped_x(const Case &c, uint32_t k, float px, float pz) {
    return c.map_c[k] * px - c.map_s[k] * pz + c.map_x[k];
}
float mapped_z(const Case &c, uint32_t k, float px, float pz) {
    return c.map_s[k] * px + c.map_c[k] * pz + c.map_z[k];
}

Case make_case(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1), r01(0, 1);
    Case c;
    const uint32_t chunks = 3 + rng() % 20;
    // Each chunk's cells lie in their own frame, at a shuffled place in memory.
    std::vector<uint32_t> slot(chunks);
    for (uint32_t k = 0; k < chunks; ++k) slot[k] = k;
    std::shuffle(slot.begin(), slot.end(), rng);
    c.x.assign(chunks * force_lanes, force_padding_position);
    c.z.assign(chunks * force_lanes, 0.0f);  // padding, as pair_forces.h lays it
    c.type.assign(chunks * force_lanes, 0);
    const uint32_t self_chunk = rng() % chunks;
    for (uint32_t k = 0; k < chunks; ++k) {
        const float angle = k == self_chunk ? 0.0f : 6.2831853f * r01(rng);
        c.first.push_back(slot[k] * force_lanes);
        c.map_c.push_back(std::cos(angle));
        c.map_s.push_back(k == self_chunk ? 0.0f : std::sin(angle));
        c.map_x.push_back(k == self_chunk ? 0.0f : u(rng));
        c.map_z.push_back(k == self_chunk ? 0.0f : u(rng));
        const float ox = u(rng), oz = u(rng), spread = 0.05f + 0.3f * r01(rng);
        const uint32_t n = 1 + rng() % force_lanes;  // the rest of the chunk is padding
        std::vector<Vec2d> at;
        for (uint32_t l = 0; l < n; ++l) {
            const uint32_t p = c.first[k] + l;
            c.x[p] = ox + spread * u(rng);
            c.z[p] = oz + spread * u(rng);
            c.type[p] = int32_t(rng() % max_cell_types);
            at.push_back(
                {mapped_x(c, k, c.x[p], c.z[p]), mapped_z(c, k, c.x[p], c.z[p])});
        }
        double lo_x = 1e30, hi_x = -1e30, lo_z = 1e30, hi_z = -1e30;
        for (const Vec2d &q : at) {
            lo_x = std::min(lo_x, q.x), hi_x = std::max(hi_x, q.x);
            lo_z = std::min(lo_z, q.y), hi_z = std::max(hi_z, q.y);
        }
        const double mx = 0.5 * (lo_x + hi_x), mz = 0.5 * (lo_z + hi_z);
        double rad = 0;
        for (const Vec2d &q : at) rad = std::max(rad, std::hypot(q.x - mx, q.y - mz));
        c.cx.push_back(float(mx));
        c.cz.push_back(float(mz));
        c.radius.push_back(float(rad) * 1.0001f + 1e-6f);
    }
    while (c.cx.size() % force_lanes) {  // padding chunks, as the relaxation lays them
        c.first.push_back(0);
        for (auto *v : {&c.map_x, &c.map_z, &c.map_s}) v->push_back(0);
        c.map_c.push_back(1);
        c.cx.push_back(force_padding_position);
        c.cz.push_back(force_padding_position);
        c.radius.push_back(0);
    }
    // The targets are the real cells of chunk `self_chunk`, then some free ones.
    c.self = c.first[self_chunk];
    for (uint32_t l = 0; l < force_lanes && c.x[c.self + l] != force_padding_position;
         ++l)
        c.tx.push_back(c.x[c.self + l]), c.tz.push_back(c.z[c.self + l]);
    for (int k = 0; k < 24; ++k) {
        if (k % 6 == 5) {  // exactly on a real cell of another chunk
            uint32_t ch, l;
            do ch = rng() % chunks, l = rng() % force_lanes;
            while (ch == self_chunk || c.x[c.first[ch] + l] == force_padding_position);
            const uint32_t p = c.first[ch] + l;
            c.tx.push_back(mapped_x(c, ch, c.x[p], c.z[p]));
            c.tz.push_back(mapped_z(c, ch, c.x[p], c.z[p]));
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
            for (uint32_t ch = 0; ch < c.cx.size(); ++ch) {
                for (uint32_t l = 0; l < force_lanes; ++l) {
                    const uint32_t p = c.first[ch] + l;
                    if (c.radius[ch] == 0 || c.x[p] == force_padding_position ||
                        p == c.self + k)
                        continue;
                    // The cell carried into the targets' frame in doubles.
                    const double px = double(c.map_c[ch]) * c.x[p] -
                                      double(c.map_s[ch]) * c.z[p] + c.map_x[ch];
                    const double pz = double(c.map_s[ch]) * c.x[p] +
                                      double(c.map_c[ch]) * c.z[p] + c.map_z[ch];
                    const double dx = double(c.tx[k]) - px, dz = double(c.tz[k]) - pz;
                    const double d = std::hypot(dx, dz);
                    if (d >= r) continue;
                    ++within;
                    // The kernel's floats put this target exactly on the cell.
                    if (c.tx[k] == mapped_x(c, ch, c.x[p], c.z[p]) &&
                        c.tz[k] == mapped_z(c, ch, c.x[p], c.z[p])) {
                        on_top = true;
                        continue;
                    }
                    const double f = (1 - d / r) * c.oma[k * 8 + c.type[p]] * r;
                    ex += dx / d * f;
                    ez += dz / d * f;
                    scale += f;
                    ++pairs;
                }
            }
            EXPECT_NEAR(s.x[k], ex, 1e-4 * scale + 1e-6) << "seed " << seed << " k " << k;
            EXPECT_NEAR(s.z[k], ez, 1e-4 * scale + 1e-6) << "seed " << seed << " k " << k;
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
