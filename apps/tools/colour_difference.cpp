#include "apps/tools/colour_difference.h"

#include <cmath>

namespace pelage::renderer {

std::array<double, 3> cie_lab(const Rgb &c) {
    // IEC 61966-2-1 linear RGB to XYZ; white = the matrix's row sums.
    const double r = c.x, g = c.y, b = c.z;
    const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    const double xn = 0.4124564 + 0.3575761 + 0.1804375, yn = 1.0,
                 zn = 0.0193339 + 0.1191920 + 0.9503041;
    // f(t) of CIE 15:2004 Eq. 8.2: a cube root above (6/29)³, linear below.
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(x / xn), fy = f(y / yn), fz = f(z / zn);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double delta_e76(const Rgb &a, const Rgb &b) {
    const auto p = cie_lab(a), q = cie_lab(b);
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                     (p[2] - q[2]) * (p[2] - q[2]));
}

}  // namespace pelage::renderer
