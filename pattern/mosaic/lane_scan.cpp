// The four-lane K-nearest scan (lane_scan.h): lanes 0-3 of each block in one SSE2 / NEON
// register, lane 4 in another.
#include "pattern/mosaic/lane_scan.h"

#include <cstring>
#include <limits>

#include "pattern/mosaic/lane_nearest.h"

namespace pelage::pattern::mosaic {
namespace {

constexpr float inf_f = std::numeric_limits<float>::infinity();

template <int K>
LaneScan scan4(const CellBlock *b, const CellBlock *e, Vec2f q) {
    static_assert((K == 1 || K == 2) && CellBlock::size == 5);
    using namespace lanes;
    // Lane l keeps the K nearest of the cells it has seen (the l-th of each block) and
    // the least distance of the others; the K nearest overall are among the lanes'.
    // Lanes 0-3 in one vector (lo), lane 4 in another (hi, lanes 5-7 +inf).
    LaneNearest<K> lo, hi;
    const Lanes4f qx = splat(q.x), qy = splat(q.y), inf4 = splat(inf_f);
    Lanes4u slot = {0, 1, 2, 3};
    for (const CellBlock *const first = b; b != e; ++b, slot += CellBlock::size) {
        // D_min² (Teo Fig. 6.2), before each block but the first: the K-th nearest so
        // far. For K = 2 the least of the lanes' nearest but f1's lane, and that lane's
        // second (when two lanes tie at f1 this is more than F2: only ever looser, which
        // scans more, not less).
        if (b != first) {
            const float f1 = hmin(vmin(lo.m0, hi.m0));
            float d_min2 = f1;
            if constexpr (K == 2) {
                const Lanes4f at = splat(f1);
                d_min2 =
                    hmin(vmin(lo.m0 == at ? lo.m1 : lo.m0, hi.m0 == at ? hi.m1 : hi.m0));
            }
            if (b->bound2 > d_min2)
                break;  // sorted by bound: all later blocks lie beyond
        }
        Lanes4f x, y;
        std::memcpy(&x, b->x, sizeof x);
        std::memcpy(&y, b->y, sizeof y);
        // squared_distance(), four at a time: the same operations, the same bits.
        const Lanes4f dx = x - qx, dy = y - qy;
        lo.add(dx * dx + dy * dy, slot);
        Lanes4f d4 = inf4;
        d4[0] = squared_distance(b->x[4], b->y[4], q);
        hi.add(d4, slot + 4);
    }
    // The nearest: the lane at f1 (exactly one, else a tie); then, for K = 2, the least
    // of the others' nearest and that lane's second. What is left bounds the rest.
    LaneScan r;
    r.stop = b;
    r.f1 = hmin(vmin(lo.m0, hi.m0));
    const Lanes4f at1 = splat(r.f1);
    const Lanes4i a_lo = lo.m0 == at1, a_hi = hi.m0 == at1;
    r.tie = r.f1 != inf_f && hcount(a_lo) + hcount(a_hi) > 1;
    r.slot1 = hor((Lanes4u(a_lo) & lo.s0) | (Lanes4u(a_hi) & hi.s0));
    r.f2 = inf_f;
    if constexpr (K == 1) {
        r.rest = hmin(
            vmin(vmin(lo.rest, hi.rest), vmin(a_lo ? inf4 : lo.m0, a_hi ? inf4 : hi.m0)));
        r.tie |= r.f1 != inf_f && r.f1 == r.rest;
    } else {
        const Lanes4f c_lo = a_lo ? lo.m1 : lo.m0, c_hi = a_hi ? hi.m1 : hi.m0;
        r.f2 = hmin(vmin(c_lo, c_hi));
        const Lanes4f at2 = splat(r.f2);
        const Lanes4i b_lo = c_lo == at2, b_hi = c_hi == at2;
        r.tie |= r.f2 != inf_f && (r.f2 == r.f1 || hcount(b_lo) + hcount(b_hi) > 1);
        r.slot2 = hor((Lanes4u(b_lo) & (a_lo ? lo.s1 : lo.s0)) |
                      (Lanes4u(b_hi) & (a_hi ? hi.s1 : hi.s0)));
        // Left in the lanes: the second of f2's lane unless it was f1's too, and the
        // others' candidates.
        const Lanes4f r_lo = b_lo ? (a_lo ? inf4 : lo.m1) : c_lo;
        const Lanes4f r_hi = b_hi ? (a_hi ? inf4 : hi.m1) : c_hi;
        r.rest = hmin(vmin(vmin(lo.rest, hi.rest), vmin(r_lo, r_hi)));
        r.tie |= r.f2 != inf_f && r.f2 == r.rest;
    }
    return r;
}

}  // namespace

LaneScanners lane_scanners(bool wide) {
    if (wide)
        if (const LaneScanners w = detail::wide_lane_scanners(); w.lanes != 0) return w;
    return {&scan4<1>, &scan4<2>, 4};
}

}  // namespace pelage::pattern::mosaic
