#include "sim/mosaic/pair_forces.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace pelage::sim {

namespace {

// The fixed order in which the eight lanes' partial sums are added.
inline float lane_sum(const float *a) {
    return ((a[0] + a[4]) + (a[2] + a[6])) + ((a[1] + a[5]) + (a[3] + a[7]));
}

}  // namespace

void add_pair_forces_scalar(const ForceTargets &targets,
                            const ForceCandidates &candidates, const ForceSums &out) {
    for (uint32_t k = 0; k < targets.count; ++k) {
        const float qx = targets.x[k], qz = targets.z[k];
        const float r = targets.r[k], r2 = r * r;
        const float *oma = targets.one_minus_alpha + size_t(k) * 8;
        const uint32_t self = targets.self + k;
        float ax[force_lanes] = {}, az[force_lanes] = {};
        bool touching = false;
        uint32_t pairs = 0;
        for (uint32_t c = 0; c < candidates.chunks; ++c) {
            if (!reaches_chunk(qx, qz, r, candidates, c)) continue;
            const float gc = candidates.map_c[c], gs = candidates.map_s[c],
                        gx = candidates.map_x[c], gz = candidates.map_z[c];
            for (uint32_t l = 0; l < force_lanes; ++l) {
                const uint32_t p = candidates.first[c] + l;
                const float px = candidates.x[p], pz = candidates.z[p];
                const float dx = qx - (gc * px - gs * pz + gx);
                const float dz = qz - (gs * px + gc * pz + gz);
                const float d2 = dx * dx + dz * dz;
                const bool in = d2 < r2 && p != self && px != force_padding_position;
                const bool zero = d2 == 0.0f;
                touching = touching || (in && zero);
                pairs += in;
                const float d = __builtin_sqrtf(zero ? 1.0f : d2);
                const float f =
                    in && !zero ? oma[candidates.type[p]] * (r / d - 1.0f) : 0.0f;
                ax[l] += dx * f;
                az[l] += dz * f;
            }
        }
        out.x[k] = lane_sum(ax);
        out.z[k] = lane_sum(az);
        out.coincident[k] = touching;
        out.pairs[k] = pairs;
    }
}

#if defined(__x86_64__)

namespace {

// add_pair_forces_scalar with its eight lanes in one AVX2 register, and eight chunks'
// circles tested at once.
__attribute__((target("avx2"))) void add_pair_forces_avx2(
    const ForceTargets &targets, const ForceCandidates &candidates,
    const ForceSums &out) {
    const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    for (uint32_t k = 0; k < targets.count; ++k) {
        const __m256 qx = _mm256_set1_ps(targets.x[k]), qz = _mm256_set1_ps(targets.z[k]);
        const __m256 r = _mm256_set1_ps(targets.r[k]);
        const __m256 r2 = _mm256_set1_ps(targets.r[k] * targets.r[k]);
        const __m256 oma = _mm256_loadu_ps(targets.one_minus_alpha + size_t(k) * 8);
        const int self = int(targets.self + k);
        __m256 ax = zero, az = zero, touching = zero;
        uint32_t pairs = 0;
        for (uint32_t c0 = 0; c0 < candidates.chunks; c0 += force_lanes) {
            const __m256 cx =
                _mm256_sub_ps(qx, _mm256_loadu_ps(candidates.centre_x + c0));
            const __m256 cz =
                _mm256_sub_ps(qz, _mm256_loadu_ps(candidates.centre_z + c0));
            const __m256 reach =
                _mm256_add_ps(r, _mm256_loadu_ps(candidates.radius + c0));
            const __m256 near =
                _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(cx, cx), _mm256_mul_ps(cz, cz)),
                              _mm256_mul_ps(reach, reach), _CMP_LE_OQ);
            for (unsigned bits = unsigned(_mm256_movemask_ps(near)); bits;
                 bits &= bits - 1) {
                const uint32_t c = c0 + uint32_t(__builtin_ctz(bits));
                const uint32_t p = candidates.first[c];
                const __m256 gc = _mm256_broadcast_ss(candidates.map_c + c),
                             gs = _mm256_broadcast_ss(candidates.map_s + c);
                const __m256 px = _mm256_loadu_ps(candidates.x + p),
                             pz = _mm256_loadu_ps(candidates.z + p);
                const __m256 mx = _mm256_add_ps(
                    _mm256_sub_ps(_mm256_mul_ps(gc, px), _mm256_mul_ps(gs, pz)),
                    _mm256_broadcast_ss(candidates.map_x + c));
                const __m256 mz = _mm256_add_ps(
                    _mm256_add_ps(_mm256_mul_ps(gs, px), _mm256_mul_ps(gc, pz)),
                    _mm256_broadcast_ss(candidates.map_z + c));
                const __m256 dx = _mm256_sub_ps(qx, mx), dz = _mm256_sub_ps(qz, mz);
                const __m256 d2 =
                    _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dz, dz));
                // Padding cells lie 1e18 away in any frame; only a chunk holding the
                // target itself needs the lane test.
                __m256 in = _mm256_cmp_ps(d2, r2, _CMP_LT_OQ);
                if (uint32_t(self) - p < force_lanes)
                    in = _mm256_andnot_ps(
                        _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                            _mm256_add_epi32(lane, _mm256_set1_epi32(int(p))),
                            _mm256_set1_epi32(self))),
                        in);
                const __m256 at_zero = _mm256_cmp_ps(d2, zero, _CMP_EQ_OQ);
                touching = _mm256_or_ps(touching, _mm256_and_ps(in, at_zero));
                pairs += uint32_t(__builtin_popcount(unsigned(_mm256_movemask_ps(in))));
                const __m256 d = _mm256_sqrt_ps(_mm256_blendv_ps(d2, one, at_zero));
                const __m256 type_oma = _mm256_permutevar8x32_ps(
                    oma, _mm256_loadu_si256(
                             reinterpret_cast<const __m256i *>(candidates.type + p)));
                __m256 f =
                    _mm256_mul_ps(type_oma, _mm256_sub_ps(_mm256_div_ps(r, d), one));
                f = _mm256_and_ps(f, _mm256_andnot_ps(at_zero, in));
                ax = _mm256_add_ps(ax, _mm256_mul_ps(dx, f));
                az = _mm256_add_ps(az, _mm256_mul_ps(dz, f));
            }
        }
        alignas(32) float lanes_x[force_lanes], lanes_z[force_lanes];
        _mm256_store_ps(lanes_x, ax);
        _mm256_store_ps(lanes_z, az);
        out.x[k] = lane_sum(lanes_x);
        out.z[k] = lane_sum(lanes_z);
        out.coincident[k] = _mm256_movemask_ps(touching) != 0;
        out.pairs[k] = pairs;
    }
}

const bool has_avx2 = [] {
    __builtin_cpu_init();  // may run before libgcc's own constructor
    return __builtin_cpu_supports("avx2") != 0;
}();

}  // namespace

bool pair_forces_use_avx2() { return has_avx2; }

void add_pair_forces(const ForceTargets &targets, const ForceCandidates &candidates,
                     const ForceSums &out) {
    if (has_avx2)
        add_pair_forces_avx2(targets, candidates, out);
    else
        add_pair_forces_scalar(targets, candidates, out);
}

#else

bool pair_forces_use_avx2() { return false; }

void add_pair_forces(const ForceTargets &targets, const ForceCandidates &candidates,
                     const ForceSums &out) {
    add_pair_forces_scalar(targets, candidates, out);
}

#endif

}  // namespace pelage::sim
