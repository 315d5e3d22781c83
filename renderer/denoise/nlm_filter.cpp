#include "renderer/denoise/nlm_filter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace pelage::renderer::denoise_detail {

namespace {

// e^−x for x ≥ 0, to 2e-5 relative (plenty for a weight), in plain arithmetic the
// compiler vectorises (std::exp does not): 2^(−x·log2 e) split into an integer power,
// set in the exponent bits, and the degree-6 Taylor polynomial of 2^f for the fraction.
// x beyond 80 is taken as 80.
inline float exp_neg(float x) {
    const float t = -std::min(x, 80.0f) * 1.44269504f;  // in [−115.4, 0]
    const int i = int(t);                               // truncates towards 0
    const float f = t - float(i);                       // in (−1, 0]
    float p = 1.5403530e-4f;                            // (ln 2)⁶ / 6!
    p = p * f + 1.3333558e-3f;
    p = p * f + 9.6181291e-3f;
    p = p * f + 5.5504109e-2f;
    p = p * f + 2.4022651e-1f;
    p = p * f + 6.9314718e-1f;
    p = p * f + 1.0f;
    int bits;
    std::memcpy(&bits, &p, 4);
    bits += i * (1 << 23);
    float r;
    std::memcpy(&r, &bits, 4);
    return r;  // at x = 80, 2⁻¹¹⁵: nothing next to a weight of 1
}

// One output row's sums over the offsets of its window: the inner loop runs along the
// row for a fixed offset, so every load is contiguous and the loop vectorises (AVX2
// where the CPU has it: each lane's arithmetic is the same IEEE operations in the same
// order as SSE2's, without FMA, so the bytes do not depend on the CPU).
__attribute__((target_clones("avx2", "default"))) void filter_row(
    const Planes &in, const FilterParams &fp, int y, float *__restrict sum_w,
    float *__restrict sum0, float *__restrict sum1, float *__restrict sum2,
    float *__restrict sum_w2v) {
    const int W = in.width, H = in.height, R = fp.radius;
    const float k2 = fp.k * fp.k;
    const float inv_sigma_n = 1.0f / fp.normal_sigma;
    const size_t row = size_t(y) * W;
    const float *g0 = &in.guide[0][row], *g1 = &in.guide[1][row], *g2 = &in.guide[2][row];
    const float *v0 = &in.guide_var[0][row], *v1 = &in.guide_var[1][row],
                *v2 = &in.guide_var[2][row];
    const float *n0 = &in.normal[0][row], *n1 = &in.normal[1][row],
                *n2 = &in.normal[2][row];
    const float *nv = &in.normal_var[row], *z = &in.depth[row], *sf = &in.surface[row];
    const float *a0 = &in.albedo[0][row], *a1 = &in.albedo[1][row],
                *a2 = &in.albedo[2][row], *av = &in.albedo_var[row];
    const float sa2 = 3 * fp.albedo_sigma * fp.albedo_sigma;
    for (int dy = -R; dy <= R; ++dy) {
        const int yq = y + dy;
        if (yq < 0 || yq >= H) continue;
        for (int dx = -R; dx <= R; ++dx) {
            const int x0 = std::max(0, -dx), x1 = std::min(W, W - dx);
            const size_t q = size_t(yq) * W + size_t(dx);  // + x: the neighbour
            const float *qg0 = &in.guide[0][q], *qg1 = &in.guide[1][q],
                        *qg2 = &in.guide[2][q];
            const float *qv0 = &in.guide_var[0][q], *qv1 = &in.guide_var[1][q],
                        *qv2 = &in.guide_var[2][q];
            const float *qn0 = &in.normal[0][q], *qn1 = &in.normal[1][q],
                        *qn2 = &in.normal[2][q];
            const float *qnv = &in.normal_var[q], *qz = &in.depth[q],
                        *qsf = &in.surface[q];
            const float *qa0 = &in.albedo[0][q], *qa1 = &in.albedo[1][q],
                        *qa2 = &in.albedo[2][q], *qav = &in.albedo_var[q];
            const float *c0 = &in.value[0][q], *c1 = &in.value[1][q],
                        *c2 = &in.value[2][q];
            const uint8_t *ok = &in.usable[q];
            const float *qvv = &in.value_var[q];
            const float dist = float(std::max(std::abs(dx), std::abs(dy)));
            const float depth_scale = 1.0f / (fp.depth_sigma * std::max(dist, 1.0f));
            for (int x = x0; x < x1; ++x) {
                // Colour: the squared difference less the variance it holds anyway,
                // over k² times the variance (Rousselle et al. 2012, eq. 8), the sum
                // of both pixels' variances as there. A glint (a bright outlier in one
                // half) thus widens its calm neighbours' gate to itself and its energy
                // is spread over them, not dropped: gating by the centre's variance
                // plus the smaller of the two kept glints from spreading but left the
                // furry cow's dark type 4-9 % darker than the reference.
                const float s0 = v0[x] + qv0[x], s1 = v1[x] + qv1[x], s2 = v2[x] + qv2[x];
                const float d0 = g0[x] - qg0[x], d1 = g1[x] - qg1[x], d2 = g2[x] - qg2[x];
                const float dc = std::max(0.0f, ((d0 * d0 - s0) / (1e-10f + k2 * s0) +
                                                 (d1 * d1 - s1) / (1e-10f + k2 * s1) +
                                                 (d2 * d2 - s2) / (1e-10f + k2 * s2)) *
                                                    (1.0f / 3.0f));
                // Features (Rousselle et al. 2013, §4.2): normals by 1 − cos, widened
                // by their own noise, and depth relative to the centre's per pixel of
                // distance. A pixel without a surface matches only another without.
                const float sp = sf[x], sq = qsf[x];
                const float cosine = n0[x] * qn0[x] + n1[x] * qn1[x] + n2[x] * qn2[x];
                const float dn = (1.0f - cosine) * inv_sigma_n /
                                 (1.0f + (nv[x] + qnv[x]) * inv_sigma_n);
                const float dz = std::abs(z[x] - qz[x]) * depth_scale /
                                 std::max(std::abs(z[x]), 1e-6f);
                const float e0 = a0[x] - qa0[x], e1 = a1[x] - qa1[x], e2 = a2[x] - qa2[x];
                // The albedo's own noise widens the gate by the smaller of the two
                // pixels' variances: two strands' pixels, both noisy, take each other
                // in, while a pixel on a cell edge (noisy: its samples fall on either
                // side) and a calm pixel beside it do not, which would be a halo.
                const float da =
                    (e0 * e0 + e1 * e1 + e2 * e2) / (sa2 + 2 * std::min(av[x], qav[x]));
                const float df = da + sp * sq * (dn + dz) + 80.0f * (sp - sq) * (sp - sq);
                const float w = float(ok[x]) * exp_neg(dc + df);
                sum_w[x] += w;
                sum0[x] += w * c0[x];
                sum1[x] += w * c1[x];
                sum2[x] += w * c2[x];
                sum_w2v[x] += w * w * qvv[x];
            }
        }
    }
}

}  // namespace

void nlm_filter(const Planes &in, const FilterParams &params, std::vector<float> out[3],
                std::vector<float> *out_var) {
    const int W = in.width, H = in.height;
    for (int c = 0; c < 3; ++c) out[c].assign(size_t(W) * H, 0.0f);
    out_var->assign(size_t(W) * H, 0.0f);
    tbb::parallel_for(0, H, [&](int y) {
        std::vector<float> sums(size_t(W) * 5, 0.0f);
        float *sw = sums.data(), *s0 = sw + W, *s1 = s0 + W, *s2 = s1 + W, *sv = s2 + W;
        filter_row(in, params, y, sw, s0, s1, s2, sv);
        const size_t row = size_t(y) * W;
        for (int x = 0; x < W; ++x) {
            const size_t i = row + size_t(x);
            if (!in.usable[i] || !(sw[x] > 0)) {  // kept as it is
                for (int c = 0; c < 3; ++c) out[c][i] = in.value[c][i];
                (*out_var)[i] = in.value_var[i];
                continue;
            }
            (*out_var)[i] = sv[x] / (sw[x] * sw[x]);
            out[0][i] = s0[x] / sw[x];
            out[1][i] = s1[x] / sw[x];
            out[2][i] = s2[x] / sw[x];
        }
    });
}

}  // namespace pelage::renderer::denoise_detail
