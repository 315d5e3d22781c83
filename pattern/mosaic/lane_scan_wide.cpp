// The eight-lane K-nearest scan (lane_scan.h): one block's five cells in one AVX2
// register (lanes 5-7 +inf), so a block costs one distance vector and one K-nearest
// update, where four lanes need two of each, and each select is one blend instruction
// where SSE2 needs three (and, andnot, or).
//
// Only these functions are compiled for AVX2 (the target attribute, not a flag for the
// whole file: an inline function from a shared header, compiled here with AVX2, could be
// the copy the linker keeps for everyone). "avx2" and not "fma": no multiply-add is
// fused, so a distance has the bits squared_distance() gives it, as in the four-lane
// scan.
#include <cstddef>
#include <cstring>
#include <limits>

#include "pattern/mosaic/lane_scan.h"

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define PELAGE_WIDE_LANES 1
#endif

namespace pelage::pattern::mosaic::detail {

#ifdef PELAGE_WIDE_LANES
namespace {

#define PELAGE_AVX2 [[gnu::target("avx2"), gnu::always_inline]] inline

using F8 = float __attribute__((vector_size(32)));
using U8 = uint32_t __attribute__((vector_size(32)));
using I8 = int32_t __attribute__((vector_size(32)));

constexpr float inf_f = std::numeric_limits<float>::infinity();

PELAGE_AVX2 F8 splat8(float v) { return F8{v, v, v, v, v, v, v, v}; }
PELAGE_AVX2 F8 vmin8(F8 a, F8 b) { return b < a ? b : a; }  // std::min's order
PELAGE_AVX2 float hmin8(F8 v) {
    v = vmin8(v, __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3));
    v = vmin8(v, __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5));
    return vmin8(v, __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6))[0];
}
PELAGE_AVX2 uint32_t hor8(U8 v) {
    v |= __builtin_shufflevector(v, v, 4, 5, 6, 7, 0, 1, 2, 3);
    v |= __builtin_shufflevector(v, v, 2, 3, 0, 1, 6, 7, 4, 5);
    return (v | __builtin_shufflevector(v, v, 1, 0, 3, 2, 5, 4, 7, 6))[0];
}
PELAGE_AVX2 int hcount8(I8 mask) {  // lanes set in a comparison's mask (-1 each)
    mask += __builtin_shufflevector(mask, mask, 4, 5, 6, 7, 0, 1, 2, 3);
    mask += __builtin_shufflevector(mask, mask, 2, 3, 0, 1, 6, 7, 4, 5);
    return -(mask + __builtin_shufflevector(mask, mask, 1, 0, 3, 2, 5, 4, 7, 6))[0];
}

// lanes::LaneNearest (lane_nearest.h), eight lanes wide.
template <int K>
struct LaneNearest8 {
    F8 m0, m1, rest;
    U8 s0, s1;
};

template <int K>
PELAGE_AVX2 void add8(LaneNearest8<K> &n, F8 d, U8 s) {
    const I8 lt0 = d < n.m0;
    if constexpr (K == 1) {
        n.rest = vmin8(n.rest, lt0 ? n.m0 : d);
    } else {
        const I8 lt1 = d < n.m1;
        n.rest = vmin8(n.rest, lt1 ? n.m1 : d);
        n.s1 = lt0 ? n.s0 : lt1 ? s : n.s1;
        n.m1 = lt0 ? n.m0 : lt1 ? d : n.m1;
    }
    n.s0 = lt0 ? s : n.s0;
    n.m0 = lt0 ? d : n.m0;
}

// scan4() of lane_scan.cpp, step for step, with lo and hi in one register.
template <int K>
[[gnu::target("avx2")]] LaneScan scan8(const CellBlock *b, const CellBlock *e, Vec2f q) {
    static_assert((K == 1 || K == 2) && CellBlock::size == 5 &&
                  offsetof(CellBlock, y) == 20 && sizeof(CellBlock) >= 20 + 32);
    const F8 inf8 = splat8(inf_f);
    LaneNearest8<K> n{inf8, inf8, inf8, U8{}, U8{}};
    const F8 qx = splat8(q.x), qy = splat8(q.y);
    const I8 cells = {-1, -1, -1, -1, -1, 0, 0, 0};  // lanes 5-7 hold no cell
    U8 slot = {0, 1, 2, 3, 4, 5, 6, 7};
    for (const CellBlock *const first = b; b != e; ++b, slot += CellBlock::size) {
        // D_min² (Teo Fig. 6.2), as scan4() computes it, before each block but the first.
        if (b != first) {
            const float f1 = hmin8(n.m0);
            const float d_min2 = K == 1 ? f1 : hmin8(n.m0 == splat8(f1) ? n.m1 : n.m0);
            if (b->bound2 > d_min2)
                break;  // sorted by bound: all later blocks lie beyond
        }
        // x[0..4] and the next three floats, y[0..4] and the next three (within the
        // block's 64 bytes); those three lanes become +inf before any arithmetic.
        F8 x, y;
        const char *raw = reinterpret_cast<const char *>(b);
        std::memcpy(&x, raw + offsetof(CellBlock, x), sizeof x);
        std::memcpy(&y, raw + offsetof(CellBlock, y), sizeof y);
        x = cells ? x : inf8;
        y = cells ? y : inf8;
        const F8 dx = x - qx, dy = y - qy;
        add8<K>(n, dx * dx + dy * dy, slot);
    }
    LaneScan r;
    r.stop = b;
    r.f1 = hmin8(n.m0);
    const I8 a = n.m0 == splat8(r.f1);
    r.tie = r.f1 != inf_f && hcount8(a) > 1;
    r.slot1 = hor8(U8(a) & n.s0);
    r.f2 = inf_f;
    if constexpr (K == 1) {
        r.rest = hmin8(vmin8(n.rest, a ? inf8 : n.m0));
        r.tie |= r.f1 != inf_f && r.f1 == r.rest;
    } else {
        const F8 c = a ? n.m1 : n.m0;
        r.f2 = hmin8(c);
        const I8 b2 = c == splat8(r.f2);
        r.tie |= r.f2 != inf_f && (r.f2 == r.f1 || hcount8(b2) > 1);
        r.slot2 = hor8(U8(b2) & (a ? n.s1 : n.s0));
        r.rest = hmin8(vmin8(n.rest, b2 ? (a ? inf8 : n.m1) : c));
        r.tie |= r.f2 != inf_f && r.f2 == r.rest;
    }
    return r;
}

}  // namespace

LaneScanners wide_lane_scanners() {
    if (!__builtin_cpu_supports("avx2")) return {};
    return {&scan8<1>, &scan8<2>, 8};
}
#else
LaneScanners wide_lane_scanners() { return {}; }
#endif

}  // namespace pelage::pattern::mosaic::detail
