// The regular n-subdivision of a triangle in barycentric coordinates, shared by the
// closest-cell index (its regions and sub-triangles) and the candidate map: n² sub-
// triangles, numbered row by row, and the one holding a barycentric point.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace pelage::pattern::mosaic {

// The barycentric (b1, b2) corners of sub-triangle (i, j, upper) of an n-subdivision.
inline std::array<std::array<double, 2>, 3> sub_triangle(uint32_t n, uint32_t i,
                                                         uint32_t j, bool upper) {
    const double s = 1.0 / n;
    if (upper)
        return {{{(i + 1) * s, j * s}, {(i + 1) * s, (j + 1) * s}, {i * s, (j + 1) * s}}};
    return {{{i * s, j * s}, {(i + 1) * s, j * s}, {i * s, (j + 1) * s}}};
}

// Sub-triangles of an n-subdivision numbered row by row: row i holds n - i lower and
// n - i - 1 upper ones, interleaved, so the n² of them are 0 … n² - 1.
inline uint32_t slot_index(uint32_t n, uint32_t i, uint32_t j, bool upper) {
    return i * (2 * n - i) + 2 * j + (upper ? 1 : 0);
}

// The sub-triangle of an n-subdivision holding barycentric point (b1, b2), clamped to the
// triangle (hits may sit a rounding error outside it).
template <typename Real>
[[gnu::always_inline]] inline uint32_t slot_at(uint32_t n, Real b1, Real b2) {
    const Real nf = Real(n);
    const Real u = std::clamp(b1 * nf, Real(0), nf);
    const Real v = std::clamp(b2 * nf, Real(0), nf - u);
    uint32_t i = std::min(uint32_t(u), n - 1), j = std::min(uint32_t(v), n - 1);
    bool upper = (u - Real(i)) + (v - Real(j)) > Real(1);
    if (i + j >= n - 1) {  // the last row of sub-triangles has no upper halves
        j = n - 1 - std::min(i, n - 1);
        upper = false;
    }
    return slot_index(n, i, j, upper);
}

}  // namespace pelage::pattern::mosaic
