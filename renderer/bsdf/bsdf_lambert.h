// Lambertian reflection: f = ρ / π.
#pragma once

#include "renderer/bsdf/bsdf.h"
#include "renderer/core/sampling.h"

namespace pelage::renderer {

class BsdfLambert {
  public:
    explicit BsdfLambert(Rgb rho) : m_rho(rho) {}

    Rgb eval(Vec3f wo, Vec3f wi) const {
        return (wo.z > 0 && wi.z > 0) ? m_rho * inv_pi : Rgb{};
    }
    float pdf(Vec3f wo, Vec3f wi) const {
        return (wo.z > 0 && wi.z > 0) ? wi.z * inv_pi : 0.0f;
    }
    std::optional<BsdfSample> sample(Vec3f wo, float /*u_lobe*/, float u1,
                                     float u2) const {
        if (wo.z <= 0) return std::nullopt;
        const Vec3f wi = sample_cosine_hemisphere(u1, u2);
        if (wi.z <= 0) return std::nullopt;
        return BsdfSample{wi, m_rho * inv_pi, wi.z * inv_pi, m_rho, false};
    }
    Rgb albedo() const { return m_rho; }

  private:
    Rgb m_rho;
};

static_assert(Bsdf<BsdfLambert>);

}  // namespace pelage::renderer
