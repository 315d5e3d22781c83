// The film: per pixel, filter-weighted sums of the beauty and the colour AOVs, and the
// values of sample 0 for AOVs that must not be averaged (depth, ids, the shader slot).
// Layers (EXR channel names, as Nuke and oiiotool expect):
//   R G B A                      beauty, scene-linear; A = coverage by geometry
//   albedo.R albedo.G albedo.B   first-hit albedo
//   N.X N.Y N.Z                  first-hit world-space shading normal
//   depth.Z                      camera-space depth of the first hit (0 = none)
//   id.object id.primitive       first-hit ids, -1 = none
//   shader.<name> × 4            the material plugin's AOV slots
#pragma once

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "renderer/core/math.h"
#include "shader/pelage_shader.h"

namespace pelage::renderer {

struct FilmSample {
    Rgb L;
    float alpha = 0;
    Rgb albedo, normal;
};

struct FilmPointAovs {
    float depth = 0;
    float object_id = -1, primitive_id = -1;
    float shader[PELAGE_SHADER_AOV_SLOTS] = {0, 0, 0, 0};
};

class Film {
  public:
    Film(int width, int height);

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
    }
    void set_point_aovs(int x, int y, const FilmPointAovs &p) {
        m_point[size_t(y * m_width + x)] = p;
    }

    // The pixel's noise for adaptive sampling: the standard error of its mean
    // luminance over √(max(mean, 10⁻⁴)) — relative to the square root of the level, so
    // that dark pixels, which tone mapping brightens, need a smaller absolute error
    // (the normalisation of Cycles' adaptive sampling). Infinite below 2 samples.
    float noise(int x, int y) const;

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
};

}  // namespace pelage::renderer
