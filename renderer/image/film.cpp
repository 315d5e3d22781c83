#include "renderer/image/film.h"

#include <sys/mman.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <new>

namespace pelage::renderer {

namespace {

// Uninitialized storage for a film buffer. At 1280×720 the film is 66 MB, touched first
// by the render: in 4 KB pages that is 16 000 page faults per render (a few per cent of
// a short one). Buffers of 2 MB and more are aligned to 2 MB and offered to the kernel
// as transparent huge pages (madvise; Debian's default THP mode), ~35 faults instead.
void *allocate_buffer(size_t bytes) {
    constexpr size_t huge = size_t(2) << 20;
    if (bytes < huge) {
        if (void *p = std::malloc(std::max<size_t>(bytes, 1))) return p;
        throw std::bad_alloc();
    }
    const size_t rounded = (bytes + huge - 1) / huge * huge;
    void *p = std::aligned_alloc(huge, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure only costs the faults
    return p;
}

}  // namespace

Film::Film(int width, int height, int cryptomatte_layers, int cryptomatte_slots,
           bool halves)
    : m_width(width),
      m_height(height),
      m_accum(static_cast<float *>(
          allocate_buffer(size_t(width) * height * accum_stride * sizeof(float)))),
      m_point(static_cast<FilmPointAovs *>(
          allocate_buffer(size_t(width) * height * sizeof(FilmPointAovs)))) {
    // Zero the buffers row by row in parallel: at 1280×720 they are 66 MB, and touching
    // them first from one thread made page faults a serial few per cent of a short
    // render.
    tbb::parallel_for(0, height, [&](int y) {
        const size_t row = size_t(y) * width;
        std::fill_n(&m_accum[row * accum_stride], size_t(width) * accum_stride, 0.0f);
        std::uninitialized_fill_n(&m_point[row], width, FilmPointAovs{});
    });
    if (halves) {
        const size_t n = size_t(width) * height * 2 * half_stride;
        m_halves.reset(static_cast<float *>(allocate_buffer(n * sizeof(float))));
        tbb::parallel_for(0, height, [&](int y) {
            const size_t row = size_t(y) * width * 2 * half_stride;
            std::fill_n(&m_halves[row], size_t(width) * 2 * half_stride, 0.0f);
        });
    }
    if (cryptomatte_layers > 0)
        m_matte = std::make_unique<CryptomatteFilm>(width, height, cryptomatte_layers,
                                                    cryptomatte_slots);
}

std::vector<float> Film::resolve() const {
    std::vector<float> out(size_t(m_width) * m_height * num_channels, 0.0f);
    for (size_t i = 0; i < size_t(m_width) * m_height; ++i) {
        const float *a = &m_accum[i * accum_stride];
        float *o = &out[i * num_channels];
        const float inv_w = a[10] > 0 ? 1.0f / a[10] : 0.0f;
        for (int c = 0; c < 10; ++c) o[c] = a[c] * inv_w;
        // A mean of unit normals is shorter than 1 at silhouettes; renormalize.
        const Vec3f n{o[7], o[8], o[9]};
        if (const float len = length(n); len > 0) {
            o[7] = n.x / len;
            o[8] = n.y / len;
            o[9] = n.z / len;
        }
        const FilmPointAovs &p = m_point[i];
        o[10] = p.depth;
        o[11] = p.object_id;
        o[12] = p.primitive_id;
        for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS; ++k) o[13 + k] = p.shader[k];
    }
    return out;
}

DenoiseInput Film::resolve_halves() const {
    DenoiseInput in;
    if (!m_halves) return in;
    in.width = m_width;
    in.height = m_height;
    const size_t n = size_t(m_width) * m_height;
    for (DenoiseHalf &h : in.half) {
        h.colour.resize(3 * n);
        h.direct.resize(3 * n);
        h.albedo.resize(3 * n);
        h.normal.resize(3 * n);
        h.depth.resize(n);
        h.count.resize(n);
    }
    tbb::parallel_for(0, m_height, [&](int y) {
        for (size_t i = size_t(y) * m_width; i < size_t(y + 1) * m_width; ++i)
            for (int k = 0; k < 2; ++k) {
                const float *a = &m_halves[(i * 2 + size_t(k)) * half_stride];
                DenoiseHalf &h = in.half[k];
                const float inv = a[9] > 0 ? 1.0f / a[9] : 0.0f;
                for (int c = 0; c < 3; ++c) {
                    h.colour[3 * i + c] = a[c] * inv;
                    h.direct[3 * i + c] = a[12 + c] * inv;
                    h.albedo[3 * i + c] = a[3 + c] * inv;
                    h.normal[3 * i + c] = a[6 + c] * inv;
                }
                h.count[i] = a[9];
                h.depth[i] =
                    a[11] > 0 ? a[10] / a[11] : std::numeric_limits<float>::infinity();
            }
    });
    return in;
}

float Film::noise(int x, int y) const {
    const float *a = &m_accum[size_t(y * m_width + x) * accum_stride];
    const float n = a[10];
    if (n < 2) return std::numeric_limits<float>::infinity();
    const float mean = luminance(Rgb{a[0], a[1], a[2]}) / n;
    // Unbiased sample variance of the luminance, then the variance of the mean.
    const float var = std::max(0.0f, (a[11] / n - mean * mean) * n / (n - 1));
    return std::sqrt(var / n) / std::sqrt(std::max(mean, 1e-4f));
}

std::vector<std::string> Film::channel_names(
    const std::vector<std::string> &shader_aov_names) {
    std::vector<std::string> n = {
        "R",   "G",   "B",   "A",       "albedo.R",  "albedo.G",    "albedo.B",
        "N.X", "N.Y", "N.Z", "depth.Z", "id.object", "id.primitive"};
    for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS; ++k)
        n.push_back("shader." +
                    (size_t(k) < shader_aov_names.size() && !shader_aov_names[k].empty()
                         ? shader_aov_names[k]
                         : std::to_string(k)));
    return n;
}

}  // namespace pelage::renderer
