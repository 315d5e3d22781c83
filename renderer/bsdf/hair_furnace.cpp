// Midpoint-rule sphere quadrature of the hair BSDF; see hair_furnace.h.
#include "renderer/bsdf/hair_furnace.h"

#include <cmath>

namespace pelage::renderer {

FurnaceResult furnace_quadrature(const HairBsdf &bsdf, Vec3f wo, int n_theta, int n_phi,
                                 bool with_pdf) {
    const double d_theta = M_PI / n_theta, d_phi = 2 * M_PI / n_phi;
    double sum[3] = {0, 0, 0}, sum_pdf = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = -M_PI / 2 + (i + 0.5) * d_theta;
        const double cos_theta = std::cos(theta), sin_theta = std::sin(theta);
        double row[3] = {0, 0, 0}, row_pdf = 0;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * d_phi;
            const Vec3f wi{float(sin_theta), float(cos_theta * std::cos(phi)),
                           float(cos_theta * std::sin(phi))};
            const Rgb f = bsdf.eval(wo, wi);
            const double abs_cos = std::abs(wi.z);
            for (int c = 0; c < 3; ++c) row[c] += f[c] * abs_cos;
            if (with_pdf) row_pdf += bsdf.pdf(wo, wi);
        }
        const double w = cos_theta * d_theta * d_phi;
        for (int c = 0; c < 3; ++c) sum[c] += row[c] * w;
        sum_pdf += row_pdf * w;
    }
    return {Rgb{float(sum[0]), float(sum[1]), float(sum[2])}, sum_pdf};
}

}  // namespace pelage::renderer
