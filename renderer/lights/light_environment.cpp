#include "renderer/lights/light_environment.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "renderer/core/sampling.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

// Index i with cdf[i] <= u < cdf[i+1]; cdf is non-decreasing from 0 to 1.
int find_interval(const float *cdf, int n, float u) {
    const int i = int(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
    return std::clamp(i, 0, n - 1);
}

}  // namespace

EnvironmentLight::EnvironmentLight(Rgb constant) : m_constant(constant) {}

EnvironmentLight::EnvironmentLight(const std::string &image, float scale,
                                   float rotation_deg) {
    auto in = OIIO::ImageInput::open(image);
    if (!in)
        throw InputError(image, 0, "",
                         "cannot read environment image: " + OIIO::geterror());
    const OIIO::ImageSpec &spec = in->spec();
    if (spec.nchannels < 1 || spec.width < 2 || spec.height < 1)
        throw InputError(image, 0, "",
                         "environment image must have at least 2×1 pixels and a channel");
    m_width = spec.width;
    m_height = spec.height;
    const int nc = spec.nchannels;
    std::vector<float> raw(size_t(m_width) * m_height * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
        throw InputError(image, 0, "",
                         "cannot read environment image: " + in->geterror());
    m_pixels.resize(size_t(m_width) * m_height);
    for (size_t i = 0; i < m_pixels.size(); ++i) {
        const float *p = &raw[i * nc];
        Rgb c = nc >= 3 ? Rgb{p[0], p[1], p[2]} : Rgb{p[0], p[0], p[0]};
        if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0)
            c = {};  // no NaN reaches a path
        m_pixels[i] = c * scale;
    }
    const float rot = rotation_deg * pi / 180;
    m_cos_rot = std::cos(rot);
    m_sin_rot = std::sin(rot);

    // --- Build the piecewise-constant distribution of luminance × sin θ ---
    m_conditional_cdf.assign(size_t(m_height) * (m_width + 1), 0.0f);
    m_marginal_cdf.assign(m_height + 1, 0.0f);
    std::vector<double> row_sum(m_height, 0.0);
    for (int y = 0; y < m_height; ++y) {
        const float sin_t = std::sin(pi * (y + 0.5f) / m_height);
        float *cdf = &m_conditional_cdf[size_t(y) * (m_width + 1)];
        double acc = 0;
        for (int x = 0; x < m_width; ++x) {
            acc += std::max(luminance(m_pixels[size_t(y) * m_width + x]), 0.0f) * sin_t;
            cdf[x + 1] = float(acc);
        }
        row_sum[y] = acc;
        for (int x = 1; x <= m_width; ++x)
            cdf[x] = acc > 0 ? cdf[x] / float(acc) : float(x) / m_width;
        cdf[m_width] = 1.0f;
    }
    double total = 0;
    for (int y = 0; y < m_height; ++y) {
        total += row_sum[y];
        m_marginal_cdf[y + 1] = float(total);
    }
    for (int y = 1; y <= m_height; ++y)
        m_marginal_cdf[y] =
            total > 0 ? m_marginal_cdf[y] / float(total) : float(y) / m_height;
    m_marginal_cdf[m_height] = 1.0f;
    // Density in (u, v) of each pixel: p = f / (∫f du dv) with f = lum · sin θ.
    m_pdf.resize(m_pixels.size());
    const double mean = total / (double(m_width) * m_height);
    // Σ lum sin θ · (2π² / (W H)) is ∫ L dω; divided by 4π.
    m_mean_lum = float(total * pi / (2.0 * m_width * m_height));
    for (int y = 0; y < m_height; ++y) {
        const float sin_t = std::sin(pi * (y + 0.5f) / m_height);
        for (int x = 0; x < m_width; ++x) {
            const size_t i = size_t(y) * m_width + x;
            m_pdf[i] = mean > 0
                           ? float(std::max(luminance(m_pixels[i]), 0.0f) * sin_t / mean)
                           : 1.0f;
        }
    }
}

void EnvironmentLight::direction_to_uv(Vec3f d, float *u, float *v) const {
    // Undo the rotation about +y.
    const float x = m_cos_rot * d.x + m_sin_rot * d.z,
                z = -m_sin_rot * d.x + m_cos_rot * d.z;
    float phi = std::atan2(z, x);
    if (phi < 0) phi += 2 * pi;
    *u = phi / (2 * pi);
    *v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / pi;
}

Vec3f EnvironmentLight::uv_to_direction(float u, float v) const {
    const float phi = 2 * pi * u, theta = pi * v;
    const float s = std::sin(theta);
    const float x = s * std::cos(phi), z = s * std::sin(phi);
    return {m_cos_rot * x - m_sin_rot * z, std::cos(theta),
            m_sin_rot * x + m_cos_rot * z};
}

Rgb EnvironmentLight::eval_image(Vec3f dir) const {
    float u, v;
    direction_to_uv(dir, &u, &v);
    const int x = std::min(int(u * m_width), m_width - 1),
              y = std::min(int(v * m_height), m_height - 1);
    return m_pixels[size_t(y) * m_width + x];
}

float EnvironmentLight::pdf(Vec3f dir) const {
    if (is_constant()) return 1 / (4 * pi);
    float u, v;
    direction_to_uv(dir, &u, &v);
    const float sin_t = std::sin(pi * v);
    if (sin_t <= 0) return 0.0f;
    const int x = std::min(int(u * m_width), m_width - 1),
              y = std::min(int(v * m_height), m_height - 1);
    // dω = 2π² sin θ du dv.
    return m_pdf[size_t(y) * m_width + x] / (2 * pi * pi * sin_t);
}

Rgb EnvironmentLight::sample(float u1, float u2, Vec3f *dir, float *pdf_out) const {
    if (is_constant()) {
        *dir = sample_uniform_sphere(u1, u2);
        *pdf_out = 1 / (4 * pi);
        return m_constant;
    }
    // --- Pick a row from the marginal, then a column from its conditional ---
    const int y = find_interval(m_marginal_cdf.data(), m_height, u2);
    const float dv = (u2 - m_marginal_cdf[y]) /
                     std::max(m_marginal_cdf[y + 1] - m_marginal_cdf[y], 1e-30f);
    const float *cdf = &m_conditional_cdf[size_t(y) * (m_width + 1)];
    const int x = find_interval(cdf, m_width, u1);
    const float du = (u1 - cdf[x]) / std::max(cdf[x + 1] - cdf[x], 1e-30f);
    const float u = (x + std::clamp(du, 0.0f, 1.0f)) / m_width,
                v = (y + std::clamp(dv, 0.0f, 1.0f)) / m_height;
    *dir = uv_to_direction(u, v);
    const float sin_t = std::sin(pi * v);
    const float p = m_pdf[size_t(y) * m_width + x];
    *pdf_out = sin_t > 0 ? p / (2 * pi * pi * sin_t) : 0.0f;
    return m_pixels[size_t(y) * m_width + x];
}

}  // namespace pelage::renderer
