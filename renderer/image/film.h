// The film: per pixel, filter-weighted sums of the beauty and the colour AOVs, and the
// values of sample 0 for AOVs that must not be averaged (depth, ids, the shader slot).
// Layers (EXR channel names, as Nuke and oiiotool expect):
//   R G B A                      beauty, scene-linear; A = coverage by geometry
//   albedo.R albedo.G albedo.B   first-hit albedo
//   N.X N.Y N.Z                  first-hit world-space shading normal
//   depth.Z                      camera-space depth of the first hit (+inf = none)
//   id.object id.primitive       first-hit ids, -1 = none
//   shader.<name>                the material plugin's named AOV slots, -1 where no
//                                plugin wrote them (background, other materials)
// and, when asked for, Cryptomatte layers accumulated over every sample
// (cryptomatte.h). Which layers are written, and as what, is image_layers.h's job.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/denoise/denoise.h"
#include "renderer/image/cryptomatte.h"
#include "shader/pelage_shader.h"

namespace pelage::renderer {

// The object layer and the material plugins' matte layers.
inline constexpr int max_cryptomatte_layers = 1 + PELAGE_SHADER_MATTE_SLOTS;

struct FilmSample {
    Rgb L;
    // The part of L the first hit's next-event estimation gathered (with what the
    // camera ray itself saw of a light): for the denoiser, which keeps this usually
    // well-sampled light's shadows and shading apart from the noisier rest.
    Rgb direct;
    float alpha = 0;
    Rgb albedo, normal;
    // The first hit's key in each of the film's Cryptomatte layers, valid where bit l
    // of `matte_set` is set (one byte to clear per sample, not the keys).
    uint64_t matte[max_cryptomatte_layers];
    uint8_t matte_set = 0;
};

struct FilmPointAovs {
    float depth = std::numeric_limits<float>::infinity();
    float object_id = -1, primitive_id = -1;
    float shader[PELAGE_SHADER_AOV_SLOTS] = {-1, -1, -1, -1};
};

class Film {
  public:
    // `cryptomatte_layers` > 0: also accumulate that many Cryptomatte layers, keeping
    // `cryptomatte_slots` ids per pixel and layer. `halves`: also keep the denoiser's
    // two half buffers (add_half).
    Film(int width, int height, int cryptomatte_layers = 0, int cryptomatte_slots = 0,
         bool halves = false);

    int width() const { return m_width; }
    int height() const { return m_height; }

    // Single writer per pixel (its tile's thread).
    void add(int x, int y, float weight, const FilmSample &s) {
        float *a = &m_accum[size_t(y * m_width + x) * accum_stride];
        a[0] += weight * s.L.x;
        a[1] += weight * s.L.y;
        a[2] += weight * s.L.z;
        a[3] += weight * s.alpha;
        a[4] += weight * s.albedo.x;
        a[5] += weight * s.albedo.y;
        a[6] += weight * s.albedo.z;
        a[7] += weight * s.normal.x;
        a[8] += weight * s.normal.y;
        a[9] += weight * s.normal.z;
        a[10] += weight;
        const float lum = luminance(s.L);
        a[11] += weight * lum * lum;
        if (s.matte_set)
            for (int l = 0; l < m_matte->layers(); ++l)
                if (s.matte_set >> l & 1) m_matte->add(x, y, l, s.matte[l], weight);
    }
    // The sample also goes to half buffer `sample & 1`: samples of even index to one,
    // odd to the other, each with its first hit's camera depth (+inf for none).
    bool has_halves() const { return m_halves != nullptr; }
    void add_half(int x, int y, uint32_t sample, const FilmSample &s, float depth) {
        float *a = &m_halves[(size_t(y * m_width + x) * 2 + (sample & 1)) * half_stride];
        a[0] += s.L.x;
        a[1] += s.L.y;
        a[2] += s.L.z;
        a[3] += s.albedo.x;
        a[4] += s.albedo.y;
        a[5] += s.albedo.z;
        a[6] += s.normal.x;
        a[7] += s.normal.y;
        a[8] += s.normal.z;
        a[9] += 1;
        if (depth < std::numeric_limits<float>::infinity()) {
            a[10] += depth;
            a[11] += 1;
        }
        a[12] += s.direct.x;
        a[13] += s.direct.y;
        a[14] += s.direct.z;
    }
    // The half buffers' means, as the denoiser takes them; empty without halves.
    DenoiseInput resolve_halves() const;

    void set_point_aovs(int x, int y, const FilmPointAovs &p) {
        m_point[size_t(y * m_width + x)] = p;
    }

    // The pixel's noise for adaptive sampling: the standard error of its mean
    // luminance over √(max(mean, 10⁻⁴)) — relative to the square root of the level, so
    // that dark pixels, which tone mapping brightens, need a smaller absolute error
    // (the normalisation of Cycles' adaptive sampling). Infinite below 2 samples.
    float noise(int x, int y) const;
    // The pixel's summed sample weight (the Cryptomatte coverage's denominator).
    float weight(int x, int y) const {
        return m_accum[size_t(y * m_width + x) * accum_stride + 10];
    }
    // The Cryptomatte accumulation, or null when none was asked for.
    const CryptomatteFilm *cryptomatte() const { return m_matte.get(); }

    static constexpr int num_channels = 4 + 3 + 3 + 1 + 2 + PELAGE_SHADER_AOV_SLOTS;
    // All layers as interleaved float channels in the order of channel_names().
    std::vector<float> resolve() const;
    static std::vector<std::string> channel_names(
        const std::vector<std::string> &shader_aov_names);

  private:
    // R G B A, albedo, normal, weight, weighted luminance²
    static constexpr int accum_stride = 12;
    int m_width, m_height;
    // Raw storage from allocate_buffer (huge pages where the kernel grants them), filled
    // in parallel by the constructor.
    struct FreeBuffer {
        void operator()(void *p) const { std::free(p); }
    };
    std::unique_ptr<float[], FreeBuffer> m_accum;
    std::unique_ptr<FilmPointAovs[], FreeBuffer> m_point;
    std::unique_ptr<CryptomatteFilm> m_matte;
    // Per pixel and half: L, albedo, normal, samples, depth sum, samples with a depth.
    static constexpr int half_stride = 15;
    std::unique_ptr<float[], FreeBuffer> m_halves;
};

}  // namespace pelage::renderer
