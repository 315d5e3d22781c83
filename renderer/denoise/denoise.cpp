#include "renderer/denoise/denoise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "renderer/denoise/nlm_filter.h"

namespace pelage::renderer {

using denoise_detail::FilterParams;
using denoise_detail::Planes;

namespace {

// The patch the error estimates are averaged over.
constexpr int selection_radius = 3;
// The albedo added to the guide's divisor.
constexpr float guide_albedo_floor = 0.05f;

void check_sizes(const DenoiseInput &in) {
    if (in.width < 0 || in.height < 0)
        throw std::invalid_argument("denoise: negative image size");
    const size_t n = size_t(in.width) * size_t(in.height);
    for (const DenoiseHalf &h : in.half)
        if (h.colour.size() != 3 * n || h.albedo.size() != 3 * n ||
            (!h.direct.empty() && h.direct.size() != 3 * n) || h.normal.size() != 3 * n ||
            h.depth.size() != n || h.count.size() != n)
            throw std::invalid_argument(
                "denoise: a half buffer's size does not match width × height");
}

bool finite3(const std::vector<float> &v, size_t i) {
    return std::isfinite(v[3 * i]) && std::isfinite(v[3 * i + 1]) &&
           std::isfinite(v[3 * i + 2]);
}

// The mean over the usable pixels of each (2r+1)² box of `src` (per plane), and the
// number of them in `count` when asked; separable, rows in parallel.
void box_mean(const std::vector<float> &src, const std::vector<uint8_t> &usable, int W,
              int H, int r, std::vector<float> *dst, std::vector<float> *count,
              bool sum_of_squares_of_count = false) {
    std::vector<float> rs(src.size()), rc(src.size());
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            float s = 0, c = 0;
            for (int d = -r; d <= r; ++d) {
                const int xx = x + d;
                if (xx < 0 || xx >= W) continue;
                const size_t i = size_t(y) * W + xx;
                if (!usable[i]) continue;
                s += src[i];
                c += 1;
            }
            rs[size_t(y) * W + x] = s;
            rc[size_t(y) * W + x] = c;
        }
    });
    dst->assign(src.size(), 0.0f);
    if (count) count->assign(src.size(), 0.0f);
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            float s = 0, c = 0;
            for (int d = -r; d <= r; ++d) {
                const int yy = y + d;
                if (yy < 0 || yy >= H) continue;
                s += rs[size_t(yy) * W + x];
                c += rc[size_t(yy) * W + x];
            }
            const size_t i = size_t(y) * W + x;
            // A mean of c independent values has 1/c of their variance: the variance
            // plane divides by c² (sum_of_squares_of_count).
            (*dst)[i] = c > 0 ? s / (sum_of_squares_of_count ? c * c : c) : 0.0f;
            if (count) (*count)[i] = c;
        }
    });
}

}  // namespace

int denoise_support_radius(const DenoiseOptions &o) {
    // The window, around each neighbour the guide's patch, and around each of its
    // pixels the variance's own patch (prepared below); around the pixel the patch its
    // error estimates are averaged over, each of whose pixels reads its own window and
    // the variance's patch.
    return selection_radius + std::max(o.window_radius, o.direct_window_radius) +
           2 * o.patch_radius;
}

namespace {

// One component of the beauty (its two halves' per-pixel means, RGB interleaved) filtered
// on the shared features in `p` and blended with its noisy mean by their estimated
// errors; `share_a`: each pixel's share of its samples in half A; `albedo_patch`: the
// albedo's patch means.
void filter_component(const std::vector<float> &ca, const std::vector<float> &cb,
                      const std::vector<float> &share_a, Planes &p,
                      const std::vector<float> (&albedo_patch)[3], int patch_radius,
                      const FilterParams &fp, float *out,
                      std::vector<float> *noisy_error = nullptr,
                      const std::vector<float> *other_error = nullptr) {
    const int W = p.width, H = p.height;
    const size_t n = size_t(W) * size_t(H);
    std::vector<float> raw_var[3];
    for (int c = 0; c < 3; ++c) {
        p.value[c].assign(n, 0.0f);
        raw_var[c].assign(n, 0.0f);
    }
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        if (!p.usable[i]) return;
        const float ia = share_a[i], ib = 1 - ia;
        for (int c = 0; c < 3; ++c) {
            p.value[c][i] = ia * ca[3 * i + c] + ib * cb[3 * i + c];
            // The variance of the pixel's mean from its two halves' difference
            // (Var(a − b) = σ²(1/na + 1/nb), Var(mean) = σ²/(na + nb)).
            const float d = ca[3 * i + c] - cb[3 * i + c];
            raw_var[c][i] = d * d * ia * ib;
        }
    });

    // The guide: each plane's patch mean; its variance: the patch mean of the pixels'
    // variances (themselves smoothed over a patch: one pair of halves is a single
    // degree of freedom) over the patch's size.
    const int r = patch_radius;
    p.value_var.assign(n, 0.0f);
    for (int c = 0; c < 3; ++c) {
        std::vector<float> smooth_var;
        box_mean(p.value[c], p.usable, W, H, r, &p.guide[c], nullptr);
        box_mean(raw_var[c], p.usable, W, H, r, &smooth_var, nullptr);
        box_mean(smooth_var, p.usable, W, H, r, &p.guide_var[c], nullptr, true);
        for (size_t i = 0; i < n; ++i) p.value_var[i] += smooth_var[i];
        // The guide is the patch's colour over its albedo (plus a floor, so a black
        // cell's coat reflection is not magnified without bound): shading, which is
        // what the weights should compare. Across a cell edge the shading goes on
        // while the colour jumps; the albedo feature still keeps the two cells apart.
        for (size_t i = 0; i < n; ++i) {
            const float f = 1.0f / (albedo_patch[c][i] + guide_albedo_floor);
            p.guide[c][i] *= f;
            p.guide_var[c][i] *= f * f;
        }
    }

    std::vector<float> filtered[3], filtered_var;
    denoise_detail::nlm_filter(p, fp, filtered, &filtered_var);

    // Where the filter's bias costs more than the noise it removes (a sharp highlight,
    // a shadow's edge at high sample counts), the noisy pixel is the better estimate.
    // Each pixel's error is estimated both ways: the noisy mean's is its variance; the
    // filtered one's its variance plus its squared bias, whose estimate is the squared
    // difference from the noisy mean less that mean's variance (the variance the
    // difference holds anyway; Li, Wu & Chuang 2012 estimate it the same way for
    // SURE). Both are averaged over a patch, since one pixel's estimate is one
    // degree of freedom (NFOR §5.3 filters its error maps likewise), and the output
    // weighs each estimate by the inverse of its error.
    std::vector<float> err_noisy(n), err_filtered(n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        float d2 = 0;
        for (int c = 0; c < 3; ++c) {
            const float d = filtered[c][i] - p.value[c][i];
            d2 += d * d;
        }
        err_noisy[i] = p.value_var[i];
        err_filtered[i] = d2 - p.value_var[i] + filtered_var[i];
    });
    std::vector<float> mse_noisy, mse_filtered;
    box_mean(err_noisy, p.usable, W, H, selection_radius, &mse_noisy, nullptr);
    box_mean(err_filtered, p.usable, W, H, selection_radius, &mse_filtered, nullptr);
    // The squared bias is clamped at 0 after the averaging, not before: clamping each
    // pixel's noisy estimate first would bias the mean upwards by a share of the
    // variance and hold back the filter everywhere.
    for (size_t i = 0; i < n; ++i) {
        if (!p.usable[i]) continue;
        const float en = mse_noisy[i], ef = std::max(mse_filtered[i], 0.0f);
        float t = en + ef > 0 ? en / (en + ef) : 1.0f;  // the filtered one's share
        // A quiet component beside a noisy one (a sun's light samples on bare skin,
        // beside its sky and bounces) keeps its noisy mean: its filter's bias would
        // cost more than the little noise it removes, and the blend's error estimates
        // are too rough to tell. Where it carries a quarter of the other's noise or
        // more (the light samples of sub-pixel strands, whose coverage is noisy), it
        // is filtered as the other is (docs/performance.md, the denoiser).
        if (other_error) {
            const float eo = (*other_error)[i];
            t *= en > 0 ? en / (en + 0.25f * eo) : 0.0f;
        }
        for (int c = 0; c < 3; ++c)
            out[3 * i + c] += t * filtered[c][i] + (1 - t) * p.value[c][i];
    }
    if (noisy_error) *noisy_error = std::move(mse_noisy);
}

}  // namespace

std::vector<float> denoise(const DenoiseInput &input, const DenoiseOptions &options,
                           DenoiseStats *stats) {
    const auto t0 = std::chrono::steady_clock::now();
    check_sizes(input);
    const int W = input.width, H = input.height;
    const size_t n = size_t(W) * size_t(H);
    const DenoiseHalf &A = input.half[0], &B = input.half[1];
    const bool split = !A.direct.empty() && !B.direct.empty();

    Planes p;
    p.width = W;
    p.height = H;
    for (int c = 0; c < 3; ++c) {
        p.albedo[c].resize(n);
        p.normal[c].resize(n);
    }
    p.normal_var.resize(n);
    p.albedo_var.assign(n, 0.0f);
    p.depth.resize(n);
    p.surface.resize(n);
    p.usable.resize(n);
    std::vector<float> passthrough(3 * n), share_a(n, 0.0f);
    std::vector<uint8_t> nonfinite(n);

    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        const float na = A.count[i], nb = B.count[i];
        const bool fa = finite3(A.colour, i) && std::isfinite(na) &&
                        (!split || finite3(A.direct, i)),
                   fb = finite3(B.colour, i) && std::isfinite(nb) &&
                        (!split || finite3(B.direct, i));
        nonfinite[i] = !fa || !fb;
        const float wa = fa && na > 0 ? na : 0.0f, wb = fb && nb > 0 ? nb : 0.0f;
        const float total = wa + wb;
        // What a pixel that cannot be filtered keeps: the mean of its finite halves.
        for (int c = 0; c < 3; ++c)
            passthrough[3 * i + c] = total > 0
                                         ? ((wa > 0 ? wa * A.colour[3 * i + c] : 0.0f) +
                                            (wb > 0 ? wb * B.colour[3 * i + c] : 0.0f)) /
                                               total
                                         : 0.0f;
        const bool ok = wa > 0 && wb > 0 && finite3(A.albedo, i) &&
                        finite3(B.albedo, i) && finite3(A.normal, i) &&
                        finite3(B.normal, i);
        p.usable[i] = ok;
        if (!ok) {
            for (int c = 0; c < 3; ++c) p.normal[c][i] = p.albedo[c][i] = 0;
            p.normal_var[i] = p.depth[i] = p.surface[i] = 0;
            return;
        }
        const float ia = wa / total, ib = wb / total;
        share_a[i] = ia;
        for (int c = 0; c < 3; ++c) {
            p.albedo[c][i] = ia * A.albedo[3 * i + c] + ib * B.albedo[3 * i + c];
            const float e = A.albedo[3 * i + c] - B.albedo[3 * i + c];
            p.albedo_var[i] += e * e * ia * ib;
        }
        float nrm[3], len2 = 0, nvar = 0;
        for (int c = 0; c < 3; ++c) {
            nrm[c] = ia * A.normal[3 * i + c] + ib * B.normal[3 * i + c];
            len2 += nrm[c] * nrm[c];
            const float d = A.normal[3 * i + c] - B.normal[3 * i + c];
            nvar += d * d * ia * ib;
        }
        const float inv = len2 > 0 ? 1.0f / std::sqrt(len2) : 0.0f;
        for (int c = 0; c < 3; ++c) p.normal[c][i] = nrm[c] * inv;
        p.normal_var[i] = nvar;
        const float za = A.depth[i], zb = B.depth[i];
        const bool ha = std::isfinite(za), hb = std::isfinite(zb);
        p.depth[i] = ha && hb ? ia * za + ib * zb : ha ? za : hb ? zb : 0.0f;
        p.surface[i] = ha || hb;
    });

    std::vector<float> albedo_patch[3];
    for (int c = 0; c < 3; ++c)
        box_mean(p.albedo[c], p.usable, W, H, options.patch_radius, &albedo_patch[c],
                 nullptr);

    FilterParams fp;
    fp.radius = options.window_radius;
    fp.k = options.k;
    fp.albedo_sigma = options.albedo_sigma;
    std::vector<float> out(3 * n, 0.0f);
    if (!split) {
        filter_component(A.colour, B.colour, share_a, p, albedo_patch,
                         options.patch_radius, fp, out.data());
    } else {
        // The first hit's light samples (a sun's shadows and shading: detail no feature
        // holds, usually sampled well) and the rest (sky and bounces: most of the noise,
        // smooth where the features are) are filtered apart and added.
        std::vector<float> rest_a(3 * n), rest_b(3 * n);
        for (size_t j = 0; j < 3 * n; ++j) {
            rest_a[j] = A.colour[j] - A.direct[j];
            rest_b[j] = B.colour[j] - B.direct[j];
        }
        std::vector<float> rest_error;
        filter_component(rest_a, rest_b, share_a, p, albedo_patch, options.patch_radius,
                         fp, out.data(), &rest_error);
        FilterParams direct = fp;
        direct.radius = options.direct_window_radius;
        filter_component(A.direct, B.direct, share_a, p, albedo_patch,
                         options.patch_radius, direct, out.data(), nullptr, &rest_error);
    }
    size_t kept = 0, bad = 0;
    for (size_t i = 0; i < n; ++i) {
        kept += !p.usable[i];
        bad += nonfinite[i];
        if (!p.usable[i])
            for (int c = 0; c < 3; ++c) out[3 * i + c] = passthrough[3 * i + c];
    }
    if (stats) {
        stats->pixels_passed_through = kept;
        stats->nonfinite_inputs = bad;
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    return out;
}

}  // namespace pelage::renderer
