// The K nearest per lane (K = 1, 2), four lanes in one register: what
// ClosestCellIndex::scan_lanes() keeps for each of a block's lanes while it walks a list,
// with selects only (no branch on which distance is smaller). GCC / Clang vector
// extensions: SSE2 on x86-64, NEON on ARM.
#pragma once

#include <cstdint>
#include <limits>

namespace pelage::pattern::mosaic::lanes {

using Lanes4f = float __attribute__((vector_size(16)));
using Lanes4u = uint32_t __attribute__((vector_size(16)));
using Lanes4i = int32_t __attribute__((vector_size(16)));

inline Lanes4f splat(float v) { return Lanes4f{v, v, v, v}; }
inline Lanes4f vmin(Lanes4f a, Lanes4f b) { return b < a ? b : a; }  // std::min's order
inline float hmin(Lanes4f v) {
    v = vmin(v, __builtin_shufflevector(v, v, 2, 3, 0, 1));
    return vmin(v, __builtin_shufflevector(v, v, 1, 0, 3, 2))[0];
}
inline uint32_t hor(Lanes4u v) {
    v |= __builtin_shufflevector(v, v, 2, 3, 0, 1);
    return (v | __builtin_shufflevector(v, v, 1, 0, 3, 2))[0];
}
inline int hcount(Lanes4i mask) {  // lanes set in a comparison's mask (-1 each)
    mask += __builtin_shufflevector(mask, mask, 2, 3, 0, 1);
    return -(mask + __builtin_shufflevector(mask, mask, 1, 0, 3, 2))[0];
}

// Four lanes' K nearest so far (m0 <= m1, in slots s0, s1) and the least distance of the
// others each has seen (rest), given one more cell per lane (d, in slot s).
template <int K>
struct LaneNearest {
    Lanes4f m0 = splat(std::numeric_limits<float>::infinity()), m1 = m0, rest = m0;
    Lanes4u s0 = {}, s1 = {};
    void add(Lanes4f d, Lanes4u s) {
        const Lanes4i lt0 = d < m0;
        if constexpr (K == 1) {
            rest = vmin(rest, lt0 ? m0 : d);
        } else {
            const Lanes4i lt1 = d < m1;
            rest = vmin(rest, lt1 ? m1 : d);
            s1 = lt0 ? s0 : lt1 ? s : s1;
            m1 = lt0 ? m0 : lt1 ? d : m1;
        }
        s0 = lt0 ? s : s0;
        m0 = lt0 ? d : m0;
    }
};

}  // namespace pelage::pattern::mosaic::lanes
